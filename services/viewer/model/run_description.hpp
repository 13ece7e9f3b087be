#pragma once
/// @file
/// The first message a page gets: what is shown (live or replay), the robot's shape and the
/// scenario's numbers the plots and legends need.

#include <string>

#include <nlohmann/json.hpp>

#include "climbsim/scenario.hpp"

namespace climbsim::viewer {

/// The downforce set-point of a scenario [N]: the reference controller's downforce_n, else the
/// robot's desired downforce (as climbsim-plot draws it).
double downforceSetpoint(const Scenario& scenario, double robot_desired_n);

/// {"type": "hello", "mode": "live"|"replay", "robot": robotShapeJson(...),
///  "scenario": {"name", "duration_s", "step_s", "setpoint_n", "start": {x_m, y_m, yaw_deg},
///  "wall"}}. Loads the scenario's robot file; throws ConfigError naming a bad file.
nlohmann::json helloJson(const std::string& mode, const Scenario& scenario);

}  // namespace climbsim::viewer
