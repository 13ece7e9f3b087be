#include "climbsim/scenario_and_robot.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

#include <filesystem>

#include "climbsim/errors.hpp"
#include "climbsim/robot_names.hpp"

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
  if (scenario_file.empty()) {
    if (robot_file.empty()) return withRobot(std::nullopt, defaultRobotFile());
    return withRobot(std::nullopt, isShippedRobotName(robot_file) ? shippedRobotFile(robot_file) : robot_file);
  }
  return scenarioAndRobot(loadScenario(scenario_file, overrides));
}

ScenarioAndRobot scenarioAndRobot(const Scenario& scenario) {
  const std::string file = scenario.robotPath();
  if (!std::filesystem::is_regular_file(file)) {
    std::string names;
    for (const auto& name : shippedRobotNames()) names += (names.empty() ? "" : ", ") + name;
    throw ConfigError(scenario.source + (scenario.robot_line > 0 ? ":" + std::to_string(scenario.robot_line) : "") +
                      ": robot = " + scenario.robot_file + ": no robot file " + file +
                      (isShippedRobotName(scenario.robot_file) ? " (shipped robots: " + names + ")"
                                                               : " (a path is resolved against the scenario's folder; a "
                                                                 "shipped robot is named without a path: " + names + ")"));
  }
  return withRobot(scenario, file);
}

}  // namespace climbsim
