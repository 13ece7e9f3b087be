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
/// checkScenarioAgainstRobot's ConfigError when they do not fit.
ScenarioAndRobot scenarioAndRobot(const Scenario& scenario);

/// What of a scenario must fit its robot: a fixed controller's valve list has one opening per
/// chamber and the robot has valves (a reservoir); a stuck valve's chamber and a failing
/// engine exist. ConfigError "<scenario>:<line>: <key> = <value>: <why>" otherwise.
void checkScenarioAgainstRobot(const Scenario& scenario, const RobotDescription& robot, const RobotGeometry& geometry);

}  // namespace climbsim
