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

/// A rigid transform between two frames, `T_A_B` maps coordinates in B to coordinates in A:
/// p_A = T_A_B * p_B. Translations in metres.
///
/// Naming convention of every pose in climbsim (docs/design.md#physics): `T_A_B` is the
/// pose of frame B in frame A, the frames separated by underscores, each a capital letter
/// (W wall/world, R robot, C camera, S scanner, B body, F a mesh index's frame) or a word
/// (`T_parent_part`, `T_world_sensor`). So T_A_B * T_B_C = T_A_C and T_B_A = T_A_B^-1.
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
