#pragma once
/// @file
/// What the page draws of the robot, from the robot geometry (common/robot): chamber outlines,
/// sealing strip centre lines, wheel contacts, and the numbers the legends need.

#include <nlohmann/json.hpp>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::viewer {

/// {"name", "body_radius_m", "sealed_radius_m", "strip_width_m", "wheel_radius_m",
///  "ambient_pa", "desired_downforce_n",
///  "chambers": [{"number", "outline": [[x, y], ...], "centroid": [x, y]}],
///  "segments": [{"name", "kind", "length_m", "line": [[x, y], ...]}],
///  "wheels": [{"chamber", "position": [x, y]}]}; points in the robot frame R [m].
nlohmann::json robotShapeJson(const RobotDescription& description, const RobotGeometry& geometry);

}  // namespace climbsim::viewer
