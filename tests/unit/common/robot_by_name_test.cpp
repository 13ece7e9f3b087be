// A scenario names its robot by name (a shipped robot) or by path (relative to the scenario's
// folder); a robot that cannot be found names the scenario's file and line, the path as
// written and as resolved.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/robot_names.hpp"
#include "climbsim/scenario_and_robot.hpp"

namespace climbsim {
namespace {

/// The shipped hold-rough scenario with its `robot:` line replaced, written outside the
/// repository; returns its path.
std::string scenarioOutside(const std::string& name, const std::string& robot) {
  std::ifstream in(std::string(CLIMBSIM_SCENARIOS_DIR) + "/hold-rough.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto at = s.find("robot: ");
  s.replace(at, s.find('\n', at) - at, "robot: " + robot);
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / ("climbsim_by_name_" + name);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "scenario.yaml").string();
  std::ofstream(path) << s;
  return path;
}

int lineOf(const std::string& path, const std::string& prefix) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.rfind(prefix, 0) == 0) return n;
  }
  return 0;
}

TEST(RobotByName, AShippedRobotIsNamedWithoutAPath) {
  EXPECT_EQ(shippedRobotNames(), (std::vector<std::string>{"cromsci", "grid-2x2", "ring-12", "single-chamber"}));
  for (const auto& name : shippedRobotNames()) {
    const ScenarioAndRobot run = loadScenarioAndRobot(scenarioOutside(name, name), {}, "");
    EXPECT_EQ(run.robot.name, name);
    EXPECT_EQ(run.robot_file, shippedRobotFile(name));
  }
}

TEST(RobotByName, ACopiedScenarioWhoseRobotPathIsGoneNamesItsLineAndBothPaths) {
  const std::string scenario = scenarioOutside("copied", "../robots/cromsci.yaml");
  try {
    loadScenarioAndRobot(scenario, {}, "");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    const std::string resolved =
        (std::filesystem::path(scenario).parent_path() / "../robots/cromsci.yaml").lexically_normal().string();
    EXPECT_EQ(m.rfind(scenario + ":" + std::to_string(lineOf(scenario, "robot:")) + ": robot = ../robots/cromsci.yaml: "
                      "no robot file " + resolved, 0),
              0u)
        << m;
    EXPECT_NE(m.find("a shipped robot is named without a path: cromsci, grid-2x2"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  try {
    loadScenarioAndRobot(scenarioOutside("typo", "cromcsi"), {}, "");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robot = cromcsi: no robot file "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(shipped robots: cromsci, grid-2x2, ring-12, single-chamber)"),
              std::string::npos)
        << e.what();
  }
}

TEST(ScenarioFitsItsRobot, AFixedValveListHasOneOpeningPerChamberAndNeedsValves) {
  const auto withValves = [](const std::string& name, const std::string& robot) {
    std::string path = scenarioOutside(name, robot);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const auto at = s.find("controller: ");
    s.replace(at, s.find('\n', at) - at, "controller: {type: fixed, valves: [1, 1, 1, 1, 1, 1, 1]}");
    std::ofstream(path) << s;
    return path;
  };
  EXPECT_EQ(loadScenarioAndRobot(withValves("fixed_cromsci", "cromsci"), {}, "").scenario->controller.valves.size(), 7u);
  const std::string grid = withValves("fixed_grid", "grid-2x2");
  try {
    loadScenarioAndRobot(grid, {}, "");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), grid + ":" + std::to_string(lineOf(grid, "controller:")) +
                                         ": controller.valves = [1, 1, 1, 1, 1, 1, 1]: 7 openings, robot 'grid-2x2' has "
                                         "4 chambers");
  }
  const std::string single = withValves("fixed_single", "single-chamber");
  try {
    loadScenarioAndRobot(single, {}, "");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robot 'single-chamber' has no reservoir and so no valves"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace climbsim
