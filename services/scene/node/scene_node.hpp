#pragma once
/// @file
/// The scene service without DDS (DESIGN.md §1.1): holds the robot pose from RobotState,
/// places the scene's moving parts and renders the depth image and the laser scan.
/// main.cpp only moves samples in and out.
///
/// Frames: RobotState gives T_W_R, the robot frame R in the wall frame W. In the scene, R is
/// the frame of the part the 3d Pose element (--pose-element) is attached to and W the frame
/// of that part's parent; the element's pose replaces the part's offset, so T_W_R is set as is.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render_scene.hpp"
#include "robot.h"
#include "scene.hpp"

namespace climbsim::scene {

/// What the node renders and from where. Values not given (std::nullopt) come from the
/// scene's camera and distance_sensor, or the renderer's defaults when the scene has none.
struct SceneNodeOptions {
  std::string pose_element = "robot_pose";  ///< 3d Pose element placed by RobotState
  std::string camera = "depth_cam";         ///< scene camera giving the mount and defaults ("" or absent: R)
  std::string laser = "laser_scanner";      ///< scene distance_sensor of the scan
  std::optional<int> depth_size_px;         ///< image side (square) [px]
  std::optional<double> depth_width_m;      ///< image side on the sealing plane [m]
  std::optional<double> near_m;             ///< highest height seen [m], in the camera frame
  std::optional<double> far_m;              ///< lowest height reported [m]
  bool quantise_8bit = false;
  DepthBackend backend = DepthBackend::kRasterizer;
  PixelTile depth_tile;                     ///< render only this part of the image (whole by default)
};

/// The camera parameters and the mount the options and the scene give: a scene camera
/// supplies width/height [px], size [m] and near/far (near_limit and far_limit are distances
/// along the view direction -z, so heights are their negatives); the options override.
/// ConfigError naming the option and value when the result is out of range.
DepthCameraParams depthCameraParams(const Scene& scene, const SceneNodeOptions& options);
/// The same from the scene's description alone (no meshes loaded): what the launcher checks
/// before a run starts.
DepthCameraParams depthCameraParams(const SceneDescription& scene, const SceneNodeOptions& options);

class SceneNode {
 public:
  /// Hands the scene's static triangles and moving parts to the renderer. ConfigError if the
  /// pose element or the laser sensor is missing, or the camera parameters are bad.
  SceneNode(Scene scene, const SceneNodeOptions& options);

  /// Applies the RobotState samples of one step in the order given (so the last valid one
  /// wins). A sample checkRobotState refuses is logged (spdlog::warn), counted and dropped; the
  /// last valid pose is held (before the first one: the XML offset).
  void applyRobotStates(const std::vector<climbsim::RobotState>& samples);

  /// Depth image in the camera frame (robot parts never in it); only the tile set here
  /// (initially SceneNodeOptions::depth_tile) when not whole. ConfigError for a tile outside
  /// the image.
  DepthImage renderDepth();
  void setDepthTile(const PixelTile& tile);
  /// Laser scan from the scene's distance_sensor; its pose in W via scannerPoseInWall().
  LaserScan scanLaser();

  /// T_W_R now in force.
  Pose robotPoseInWall() const;
  /// T_W_S of the laser scanner now.
  Pose scannerPoseInWall() const;
  /// T_world_C of the depth camera now.
  Pose cameraPose() const;

  const DepthCameraParams& camera() const { return camera_params_; }
  const Scene& scene() const { return scene_; }
  /// Part ids left out of the depth image (the subtree the pose element moves).
  const std::vector<std::uint32_t>& robotPartIds() const { return robot_ids_; }
  std::uint64_t droppedRobotStates() const { return dropped_; }
  std::size_t staticTriangleCount() const { return renderer_->staticTriangleCount(); }

 private:
  void placeBodies();
  std::vector<std::uint32_t> hiddenParts(bool with_robot) const;

  Scene scene_;
  SceneNodeOptions options_;
  DepthCameraParams camera_params_;
  LaserParams laser_params_;
  std::size_t robot_part_ = 0;
  std::size_t wall_part_ = 0;
  std::optional<std::size_t> camera_index_;
  std::optional<std::size_t> laser_index_;
  std::vector<std::uint32_t> robot_ids_;
  std::unique_ptr<RenderScene> renderer_;
  std::vector<std::pair<std::uint32_t, RenderScene::BodyId>> bodies_;  ///< moving part -> body
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim::scene
