#pragma once
/// @file
/// A picture of a robot file, seen from outside (robot frame x to the right, y up): the body,
/// each chamber's outline with its number, every sealing strip at its width with its name, the
/// wheels with their kind, and the air path (reservoir, valves and engines, or engines on their
/// chambers). `./deploy/climbsim robot show FILE --out PNG` draws it (docs/robot-files.md).

#include <opencv2/core.hpp>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::robot {

/// Draws `description` (validated) and its geometry on a white canvas `width_px` wide; the
/// robot takes the left part, the air path and the legend the right.
cv::Mat drawRobot(const RobotDescription& description, const RobotGeometry& geometry, int width_px = 1200);

}  // namespace climbsim::robot
