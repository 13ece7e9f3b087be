#include "scene_node.hpp"

#include <spdlog/spdlog.h>

#include "scene_translate.hpp"

namespace climbsim::scene {

SceneNode::SceneNode(Scene scene, const SceneNodeOptions& options)
    : model_(std::move(scene), options), state_(model_.initialState()) {}

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

SceneOutputs SceneNode::stepModel(bool depth, bool laser) {
  SceneInputs inputs;
  inputs.T_W_R = pose_;
  inputs.depth = depth;
  inputs.laser = laser;
  pose_.reset();
  return model_.step(state_, inputs, 0, 0);
}

DepthImage SceneNode::renderDepth() { return std::move(*stepModel(true, false).depth); }

LaserScan SceneNode::scanLaser() { return std::move(*stepModel(false, true).laser); }

DepthImage SceneNode::step(std::int64_t, std::int64_t, const std::vector<climbsim::RobotState>& samples) {
  applyRobotStates(samples);
  return renderDepth();
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
