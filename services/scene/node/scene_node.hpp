#pragma once
/// @file
/// The scene service without DDS (docs/design.md#models): RobotState samples in, the scene model
/// (model/scene_model.hpp) stepped, its depth images and laser scans out. main.cpp only moves
/// samples in and out. RobotState gives T_W_R, the robot frame R in the wall frame W.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "depth_frames.hpp"
#include "robot.h"
#include "scene_model.hpp"

namespace climbsim::scene {

/// The scene model's parameters, under the name the services' options use.
using SceneNodeOptions = SceneParams;

/// The scene service's translation around SceneModel::step: checks and translates the
/// RobotState samples of a step into the model's input pose; the model's state lives here.
class SceneNode {
 public:
  using Model = SceneModel;  ///< the model it steps (model_contract.hpp)

  /// The model of `scene` (SceneModel's ConfigErrors) at its initial state. With a masked
  /// `frames` choice (DepthFrameChoice::masked) the frames step() and renderDepthAt() render are
  /// whole only where WholeDepthFrames says so, else the whole sealing's pixels
  /// (wholeSealingTiles: ConfigErrors as ShardTiles'); options.depth_tile_for_bound is then
  /// replaced.
  SceneNode(Scene scene, const SceneNodeOptions& options, const DepthFrameChoice& frames = {});

  /// Applies the RobotState samples of one step in the order given (so the last valid one
  /// wins). A sample checkRobotState refuses is logged (spdlog::warn), counted and dropped; the
  /// last valid pose is held (before the first one: the XML offset).
  void applyRobotStates(const std::vector<climbsim::RobotState>& samples);

  /// Depth image in the camera frame (robot parts never in it); only the tile set here
  /// (initially SceneNodeOptions::depth_tile) when not whole. ConfigError for a tile outside
  /// the image. `whole`: render every pixel this once, whatever the tile (a masked run's whole
  /// frames).
  DepthImage renderDepth(bool whole = false);
  /// The depth frame of the step at t_ns [ns]: with a masked DepthFrameChoice whole when
  /// WholeDepthFrames says so, else renderDepth(). Steps must come in order of time.
  DepthImage renderDepthAt(std::int64_t t_ns);
  /// Whether the last depth frame was rendered whole.
  bool lastDepthWhole() const { return last_whole_; }
  void setDepthTile(const PixelTile& tile) { model_.setDepthTile(tile); }
  /// Laser scan from the scene's distance_sensor; its pose in W via scannerPoseInWall().
  LaserScan scanLaser();
  /// One depth step in the lockstep's shape (t_ns, dt_ns, the samples of each input):
  /// applyRobotStates(samples), then renderDepthAt(t_ns). The scene has no dynamics: the
  /// clock's time chooses only which frames are whole.
  DepthImage step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::RobotState>& samples);

  /// T_W_R now in force.
  Pose robotPoseInWall() const;
  /// T_W_S of the laser scanner now.
  Pose scannerPoseInWall() const;
  /// T_world_C of the depth camera now (world: the scene's ROOT frame).
  Pose cameraPose() const;

  const DepthCameraParams& camera() const { return model_.camera(); }
  const Scene& scene() const { return model_.scene(); }
  /// Part ids left out of the depth image (the subtree the pose element moves).
  const std::vector<std::uint32_t>& robotPartIds() const { return model_.robotPartIds(); }
  std::uint64_t droppedRobotStates() const { return dropped_; }
  std::size_t staticTriangleCount() const { return model_.staticTriangleCount(); }

 private:
  /// The model of `scene` with `options` as they are (the public constructor's masked options).
  SceneNode(const SceneNodeOptions& options, Scene&& scene, const DepthFrameChoice& frames);
  /// One model step with the pose applied since the last one.
  SceneOutputs stepModel(bool depth, bool laser, bool depth_whole = false);

  SceneModel model_;
  SceneState state_;
  std::optional<Pose> pose_;  ///< the last valid pose applied since the last step
  std::uint64_t dropped_ = 0;
  WholeDepthFrames whole_frames_;
  bool masked_ = false;  ///< DepthFrameChoice::masked
  bool last_whole_ = false;
};

}  // namespace climbsim::scene
