#pragma once
/// @file
/// What every service's configure function starts from (docs/design.md#configuration): the
/// run's scenario, if the service was started with one, and the robot description, from the
/// scenario, else from --robot, else the default robot (deploy/robots/cromsci.yaml). A service
/// main loads it from its command line; climbsim solo makes it from the scenario it runs.

#include <optional>
#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"

namespace climbsim {

struct ScenarioAndRobot {
  std::optional<Scenario> scenario;  ///< empty: a service started without --scenario
  std::string robot_file;            ///< the file `robot` was read from
  RobotDescription robot;
  RobotGeometry geometry;            ///< computeGeometry(robot)
};

/// The robot file of the default robot, deploy/robots/cromsci.yaml.
const std::string& defaultRobotFile();

/// Reads `scenario_file` with `overrides` (loadScenario; "" for none) and the robot it names,
/// or else `robot_file` (--robot; "" for the default robot). ConfigErrors as loadScenario and
/// loadRobotDescription give them.
ScenarioAndRobot loadScenarioAndRobot(const std::string& scenario_file, const std::vector<std::string>& overrides,
                                      const std::string& robot_file = "");

/// The robot `scenario` names, with the scenario: what a run of that scenario configures.
ScenarioAndRobot scenarioAndRobot(const Scenario& scenario);

}  // namespace climbsim
