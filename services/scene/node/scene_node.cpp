#include "scene_node.hpp"

#include <spdlog/spdlog.h>

#include "scene_translate.hpp"
#include "shard_tile.hpp"

namespace climbsim::scene {

namespace {

/// `options` with the whole sealing's tiles as the depth tile for a masked choice.
SceneNodeOptions maskedTo(const Scene& scene, SceneNodeOptions options, const DepthFrameChoice& frames) {
  if (frames.masked()) {
    options.depth_tile_for_bound = wholeSealingTiles(frames.robot_file, depthCameraParams(scene, options), frames.subpixel);
  }
  return options;
}

}  // namespace

SceneNode::SceneNode(Scene scene, const SceneNodeOptions& options, const DepthFrameChoice& frames)
    : SceneNode(maskedTo(scene, options, frames), std::move(scene), frames) {}

SceneNode::SceneNode(const SceneNodeOptions& options, Scene&& scene, const DepthFrameChoice& frames)
    : model_(std::move(scene), options), state_(model_.initialState()), whole_frames_(frames), masked_(frames.masked()) {}

void SceneNode::applyRobotStates(const std::vector<climbsim::RobotState>& samples) {
  for (const auto& sample : samples) {
    const std::string problem = checkRobotState(sample);
    if (!problem.empty()) {
      ++dropped_;
      spdlog::warn("scene: dropped {} (dropped so far: {}); holding the last valid pose", problem, dropped_);
      continue;
    }
    pose_ = robotPoseFromIdl(sample);
  }
}

SceneOutputs SceneNode::stepModel(bool depth, bool laser, bool depth_whole) {
  SceneInputs inputs;
  inputs.T_W_R = pose_;
  inputs.depth = depth;
  inputs.depth_whole = depth_whole;
  inputs.laser = laser;
  pose_.reset();
  return model_.step(state_, inputs, 0, 0);
}

DepthImage SceneNode::renderDepth(bool whole) {
  DepthImage image = std::move(*stepModel(true, false, whole).depth);
  last_whole_ = image.tile.whole();
  return image;
}

DepthImage SceneNode::renderDepthAt(std::int64_t t_ns) {
  // Without a masked choice the frame is as the options give it (whole, or a --tile's tile).
  return renderDepth(masked_ && whole_frames_.whole(t_ns));
}

LaserScan SceneNode::scanLaser() { return std::move(*stepModel(false, true).laser); }

DepthImage SceneNode::step(std::int64_t t_ns, std::int64_t /*dt_ns*/, const std::vector<climbsim::RobotState>& samples) {
  applyRobotStates(samples);
  return renderDepthAt(t_ns);
}

Pose SceneNode::robotPoseInWall() const { return pose_ ? *pose_ : state_.T_W_R; }

Pose SceneNode::scannerPoseInWall() const {
  SceneState now = state_;
  if (pose_) now.T_W_R = *pose_;
  return model_.scannerPoseInWall(now);
}

Pose SceneNode::cameraPose() const {
  SceneState now = state_;
  if (pose_) now.T_W_R = *pose_;
  return model_.cameraPose(now);
}

}  // namespace climbsim::scene
