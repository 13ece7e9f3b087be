#include "climbsim/scenario_and_robot.hpp"

#ifndef CLIMBSIM_DEFAULT_ROBOT_FILE
#error "CLIMBSIM_DEFAULT_ROBOT_FILE must name the default robot description"
#endif

#include <filesystem>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/robot_names.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim {
namespace {
ScenarioAndRobot withRobot(std::optional<Scenario> scenario, std::string robot_file) {
  ScenarioAndRobot out{std::move(scenario), std::move(robot_file), {}, {}};
  out.robot = loadRobotDescription(out.robot_file);
  out.geometry = computeGeometry(out.robot);
  if (out.scenario) checkScenarioAgainstRobot(*out.scenario, out.robot, out.geometry);
  return out;
}

std::string where(const Scenario& scenario, int line) {
  return scenario.source + (line > 0 ? ":" + std::to_string(line) : "");
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
    return withRobot(std::nullopt, robotFileOf(robot_file));
  }
  return scenarioAndRobot(loadScenario(scenario_file, overrides));
}

void checkScenarioAgainstRobot(const Scenario& scenario, const RobotDescription& robot, const RobotGeometry& geometry) {
  const auto& valves = scenario.controller.valves;
  if (scenario.controller.kind == Scenario::ControllerKind::kFixed) {
    std::string list;
    for (double v : valves) {
      std::ostringstream text;
      text << v;
      list += (list.empty() ? "" : ", ") + text.str();
    }
    if (!geometry.has_reservoir) {
      throw ConfigError(where(scenario, scenario.controller.valves_line) + ": controller.valves = [" + list +
                        "]: robot '" + robot.name + "' has no reservoir and so no valves");
    }
    if (valves.size() != static_cast<std::size_t>(geometry.chamberCount())) {
      throw ConfigError(where(scenario, scenario.controller.valves_line) + ": controller.valves = [" + list + "]: " +
                        std::to_string(valves.size()) + " openings, robot '" + robot.name + "' has " +
                        std::to_string(geometry.chamberCount()) + " chambers");
    }
  }
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
