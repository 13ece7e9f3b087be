#pragma once
/// @file
/// An indexed triangle mesh as the generator writes it (single precision, like the files).

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace climbsim::surface {

/// Triangles are counter-clockwise seen from outside (outward normals).
struct SurfaceMesh {
  std::vector<Eigen::Vector3f> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace climbsim::surface
