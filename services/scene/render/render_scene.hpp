#pragma once
/// @file
/// The scene's sensors on world-frame triangles: the orthographic depth camera under the
/// robot and the 2D laser scanner (docs/design.md#models). No scene XML, no DDS: the scene graph
/// hands over the static geometry once (preprocessed here once: the rasteriser's box tree and
/// Embree's BVH) and the poses of moving bodies whenever they change.
///
/// Usage (the scene node):
///
///   RenderScene sensors(static_mesh_W);                      // wall, millions of triangles
///   const auto robot = sensors.addBody(robot_mesh_R, T_W_R); // moving parts, own frame
///   ...each step:
///   sensors.setBodyPose(robot, T_W_R);
///   sensors.renderDepth(T_W_R, camera, robot_part_ids, depth);  // robot switched off
///   sensors.scanLaser(T_W_S, laser, {}, scan);
///
/// Part ids come from TriangleMesh::part_ids and are the caller's choice; a part id listed in
/// `excluded_part_ids` is invisible to that one call (ids that appear nowhere are ignored).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "depth_camera.hpp"
#include "depth_rasterizer.hpp"
#include "laser_scanner.hpp"
#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// Construction options.
struct RenderOptions {
  /// Backend of renderDepth() without an explicit backend; the faster one by the benchmark.
  DepthBackend depth_backend = DepthBackend::kRasterizer;
  /// rtcNewDevice's configuration; "threads=1" builds the BVH on one core (the service's
  /// share of the machine). Rays are cast on the calling thread whatever it says.
  std::string embree_device_config = "threads=1";
  /// false: no Embree scene is built (its BVH over the static mesh is most of a scene's
  /// loading time): laser scans and the kEmbree depth backend are then refused
  /// (std::logic_error); the rasteriser's depth images are the same bit for bit.
  bool embree = true;
  /// The rasteriser's kernel variant; kAuto: the widest this CPU runs (the others are for
  /// benchmarks and tests; all give the same image). A variant the CPU lacks is an error at
  /// the first rasterised frame (std::invalid_argument).
  RasterKernel raster_kernel = RasterKernel::kAuto;
  /// true: the reference rasteriser (every batch of a leaf in view set up in full, each
  /// sample of an area-weighted edge pixel a pass of its own), against which the default
  /// path's images are checked bit for bit (tests, climbsim-bench-scene --crack-descent).
  bool reference_raster = false;
  /// Where the rasteriser's index of a large static mesh is kept between runs
  /// (triangle_index_cache.hpp; the scene model passes climbsim::cacheDir()); nullopt: built at
  /// every start. The images are the same bit for bit either way.
  std::optional<std::filesystem::path> index_cache_dir;
};

/// Static geometry, moving bodies and the two sensors on them. Not thread-safe: one caller.
class RenderScene {
 public:
  using BodyId = std::size_t;

  /// static_mesh_W: every part that never moves, in the world frame W [m]. Builds the Embree
  /// scene and, when options.depth_backend is the rasteriser, its index (the other backend's
  /// index is built on first use). Throws climbsim::ConfigError naming the mesh, the triangle
  /// and the value for out-of-range indices, non-finite vertices or a part id count that
  /// differs from the triangle count.
  explicit RenderScene(const TriangleMesh& static_mesh_W, const RenderOptions& options = {});
  ~RenderScene();
  RenderScene(RenderScene&&) noexcept;
  RenderScene& operator=(RenderScene&&) noexcept;

  /// Adds a rigid moving body (e.g. the robot: chassis, wheels) with its triangles in its own
  /// frame B, placed at T_W_B. Same checks as the constructor.
  BodyId addBody(const TriangleMesh& mesh_B, const Pose& T_W_B = Pose::Identity());
  /// Moves a body; cheap (no rebuild of its geometry). Throws std::out_of_range for an
  /// unknown id, std::invalid_argument for a non-finite pose.
  void setBodyPose(BodyId body, const Pose& T_W_B);

  /// Depth image of the camera whose frame C is at T_W_C (C = robot frame R: z away
  /// from the wall, looking along -z); semantics in depth_camera.hpp. Throws ConfigError for
  /// bad camera parameters, std::invalid_argument for a non-finite pose. `image` is resized.
  void renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                   const std::vector<std::uint32_t>& excluded_part_ids, DepthBackend backend, DepthImage& image);
  /// Same with the default backend.
  void renderDepth(const Pose& T_W_C, const DepthCameraParams& camera,
                   const std::vector<std::uint32_t>& excluded_part_ids, DepthImage& image);
  /// An upper bound of every height [m] the image of the camera at T_W_C can hold, from the
  /// boxes of the triangle index's leaves in view (depthTopBound) plus 10 µm for the float
  /// arithmetic of the rasteriser, within [far_m, near_m]: cheap (no pixel is rendered), so that
  /// a sealing shard's tile can be chosen for the frame (SceneParams::depth_tile_for_bound).
  double depthHeightBound(const Pose& T_W_C, const DepthCameraParams& camera,
                          const std::vector<std::uint32_t>& excluded_part_ids);
  DepthImage renderDepth(const Pose& T_W_C, const DepthCameraParams& camera = {},
                         const std::vector<std::uint32_t>& excluded_part_ids = {});

  /// Laser scan from the scanner frame S at T_W_S (beams in S's x-y plane, see
  /// laser_scanner.hpp). Always on Embree.
  void scanLaser(const Pose& T_W_S, const LaserParams& laser,
                 const std::vector<std::uint32_t>& excluded_part_ids, LaserScan& scan);
  LaserScan scanLaser(const Pose& T_W_S, const LaserParams& laser = {},
                      const std::vector<std::uint32_t>& excluded_part_ids = {});

  /// What the last renderDepth() with the rasteriser visited (static mesh and bodies); zero
  /// after an Embree frame.
  const RasterCounters& lastDepthCounters() const;

  std::size_t staticTriangleCount() const;
  DepthBackend defaultDepthBackend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace climbsim::scene
