#include "climbsim/scenario_and_robot.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

namespace climbsim {
namespace {
ScenarioAndRobot withRobot(std::optional<Scenario> scenario, std::string robot_file) {
  ScenarioAndRobot out{std::move(scenario), std::move(robot_file), {}, {}};
  out.robot = loadRobotDescription(out.robot_file);
  out.geometry = computeGeometry(out.robot);
  return out;
}
}  // namespace

const std::string& defaultRobotFile() {
  static const std::string file = CLIMBSIM_DEFAULT_ROBOT_FILE;
  return file;
}

ScenarioAndRobot loadScenarioAndRobot(const std::string& scenario_file, const std::vector<std::string>& overrides,
                                      const std::string& robot_file) {
  if (scenario_file.empty()) return withRobot(std::nullopt, robot_file.empty() ? defaultRobotFile() : robot_file);
  Scenario scenario = loadScenario(scenario_file, overrides);
  std::string file = scenario.robotPath();
  return withRobot(std::move(scenario), std::move(file));
}

ScenarioAndRobot scenarioAndRobot(const Scenario& scenario) { return withRobot(scenario, scenario.robotPath()); }

}  // namespace climbsim
