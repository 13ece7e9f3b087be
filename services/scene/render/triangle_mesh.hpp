#pragma once
/// @file
/// The geometry handed from the scene graph to the sensors: triangles in one frame (the
/// scene's world frame), each tagged with the part it came from, so that the depth camera
/// can leave out the robot's own parts.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace climbsim::scene {

/// A rigid transform between two frames, `T_AB` maps coordinates in B to coordinates in A:
/// p_A = T_AB * p_B. Translations in metres.
using Pose = Eigen::Isometry3d;

/// Triangles of all visible parts, in the world frame [m]. Vertex order is free (both sides
/// of a triangle are hit).
struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< indices into vertices_m
  /// One entry per triangle: the id of the part it belongs to (index into the scene's
  /// parts, or any id the caller chooses).
  std::vector<std::uint32_t> part_ids;
};

}  // namespace climbsim::scene
