#pragma once
/// @file
/// The run's robot body in a scene (docs/scene-files.md#the-robot-body): a scene whose robot
/// parts carry no mesh (the default pylon, deploy/scenes/*.xml) gets the body generated from
/// the robot file as a part under the robot's pose; a scene that models the robot itself keeps
/// its own meshes.

#include <string>

#include "climbsim/wall/scene_description.hpp"

namespace climbsim::scene {

/// Name of the part that carries the robot body (under the pose element's part, offset zero).
inline constexpr const char* kRobotBodyPart = "ROBOT_BODY";

/// Adds part kRobotBodyPart carrying `body` (triangles in the robot frame R) under the part the
/// 3d Pose element `pose_element` moves, when neither that part nor any part below it carries
/// a mesh; returns whether it did. A scene without that element is left as it is (the scene
/// model names the missing element).
bool attachRobotBody(SceneDescription& scene, const std::string& pose_element, LocalMesh body);

}  // namespace climbsim::scene
