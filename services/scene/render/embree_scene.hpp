#pragma once
/// @file
/// The sensors on Embree 3: the static wall in one scene committed once (one geometry per
/// part, so that parts can be left out by an intersection-context filter without a rebuild),
/// moving bodies as instances in a second, small scene whose transforms follow the bodies.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "depth_camera.hpp"
#include "laser_scanner.hpp"
#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

class EmbreeScene {
 public:
  /// static_mesh_W: triangles in the world frame; slot_of_triangle: the part slot of each
  /// (< slot_count). device_config is rtcNewDevice's string ("threads=1": build on one core).
  EmbreeScene(const TriangleMesh& static_mesh_W, const std::vector<std::uint32_t>& slot_of_triangle,
              const std::string& device_config);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// Adds a rigid body with triangles in its own frame B at pose T_W_B; returns its index.
  std::size_t addBody(const TriangleMesh& mesh_B, const std::vector<std::uint32_t>& slot_of_triangle, const Pose& T_W_B);
  void setBodyPose(std::size_t body, const Pose& T_W_B);

  /// z_buffer (W * H, row-major): z_C of the first surface below near along each pixel's ray
  /// when it lies at or above far, -inf otherwise. Slots with slot_excluded[slot] != 0 are
  /// not seen (slot_excluded may be empty: nothing excluded).
  void renderDepth(const Pose& T_W_C, const DepthCameraParams& camera, const std::vector<char>& slot_excluded,
                   std::vector<float>& z_buffer);

  /// ranges (beam_count): distance to the first surface in [range_min, range_max], +inf otherwise.
  void scan(const Pose& T_W_S, const LaserParams& laser, const std::vector<char>& slot_excluded,
            std::vector<float>& ranges);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace climbsim::scene
