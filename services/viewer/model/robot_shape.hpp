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
///  "wheels": [{"chamber", "kind", "radius_m", "position": [x, y]}],
///  "body_mesh": {"positions": [x0, y0, z0, x1, ...], "indices": [a0, b0, c0, ...],
///                "body_triangles": the first triangles, the body's; the wheels' follow}};
/// points in the robot frame R [m]. The body mesh is surface::robotBodyMesh, the scene's.
nlohmann::json robotShapeJson(const RobotDescription& description, const RobotGeometry& geometry);

}  // namespace climbsim::viewer
