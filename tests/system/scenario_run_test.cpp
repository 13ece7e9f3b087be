// Whole scenario runs through the launcher, as a user starts them: `climbsim-compose run`
// with every service of deploy/compose.yaml as a separate process on real Fast DDS.

#include <gtest/gtest.h>

#include "launcher_run.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace {

using namespace climbsim::system_test;

/// The downforce column of trace.csv.
std::vector<double> downforce(const fs::path& trace) {
  std::vector<double> out;
  std::istringstream lines(readFile(trace));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) out.push_back(std::strtod(line.c_str() + line.find(',') + 1, nullptr));
  return out;
}

TEST(ScenarioRun, CrackDescentCompletesOnTheWallAndRepeatsBitForBit) {
  // 8 s: held for 2 s, then 0.3 m down the wall towards the crack.
  const auto first = runScenario("system-crack-descent-1", "crack-descent --set duration_s=8");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string summary = readFile(first.dir / "summary.json");
  EXPECT_NE(summary.find("\"completed\": true"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"fell\": false"), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(first.dir / "scenario.yaml"));
  // The launcher plots every run; the scenario asks for pictures at 1, 5 and 7 s (of 8).
  for (const char* plot : {"downforce.png", "pressures.png", "valves.png", "wheel_loads.png", "ring_5s.png"}) {
    EXPECT_GT(fs::exists(first.dir / "plots" / plot) ? fs::file_size(first.dir / "plots" / plot) : 0u, 1000u) << plot;
  }
  EXPECT_TRUE(fs::exists(first.dir / "pictures" / "sealing_gaps_7s.png"));
  const auto f = downforce(first.dir / "trace.csv");
  ASSERT_EQ(f.size(), 1600u);
  // Once the vacuum is built the reference controller keeps the robot well above what it
  // needs to hold (m g / mu = 631 N) on rough concrete.
  for (std::size_t k = 400; k < f.size(); ++k) ASSERT_GT(f[k], 1000.0) << "row " << k;

  const auto second = runScenario("system-crack-descent-2", "crack-descent --set duration_s=8");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(readFile(first.dir / "trace.csv") == readFile(second.dir / "trace.csv"))
      << "the same scenario gave a different trace";
}

TEST(ScenarioRun, EveryShippedScenarioGivesTheSameTraceAtWindowOneAndTheDefaultWindow) {
  // The stamped data are the promise; the window only bounds the run-ahead. 5 s of each:
  // the 2 s hold, the release and the first metres (faults at 6 s are covered by the unit
  // and integration tests of thermo).
  for (const char* scenario : {"crack-descent", "climb-up", "engine-failure", "hold-rough", "overhang", "valve-stuck"}) {
    const auto lockstep = runScenario(std::string("window1-") + scenario,
                                      std::string(scenario) + " --set duration_s=5 --window-steps 1");
    ASSERT_EQ(lockstep.exit_code, 0) << scenario << "\n" << lockstep.output;
    const auto horizon = runScenario(std::string("window-default-") + scenario,
                                     std::string(scenario) + " --set duration_s=5");
    ASSERT_EQ(horizon.exit_code, 0) << scenario << "\n" << horizon.output;
    const std::string a = readFile(lockstep.dir / "trace.csv");
    EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 1001) << scenario << ": a header and 1000 rows";
    EXPECT_TRUE(a == readFile(horizon.dir / "trace.csv")) << scenario << ": W = 1 and the default W differ";
  }
}

TEST(ScenarioRun, AWindowDeeperThanTheQueuesStopsBeforeStepZeroWithOneLine) {
  const auto r = runScenario("system-window-too-deep", "crack-descent --set duration_s=3 --window-steps 100");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.find("starting"), std::string::npos) << "nothing may start\n" << r.output;
  EXPECT_NE(r.output.find("window_steps (--window-steps) = 100: above 32"), std::string::npos) << r.output;
  const std::string trace = fs::exists(r.dir / "trace.csv") ? readFile(r.dir / "trace.csv") : std::string();
  EXPECT_LE(std::count(trace.begin(), trace.end(), '\n'), 1) << "no step may run: at most the header";
}

TEST(ScenarioRun, ABadScenarioStopsBeforeAnythingStartsWithOneLine) {
  const auto r = runScenario("system-bad-scenario", "crack-descent --set controller.type=magic");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("crack-descent.yaml (--set controller.type=magic): controller.type = magic"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

TEST(ScenarioRun, ARobotFileThatDoesNotLoadStopsBeforeAnythingStarts) {
  const fs::path robot = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "bad-robot.yaml";
  fs::create_directories(robot.parent_path());
  std::string text = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / "robots" / "cromsci.yaml");
  const auto mass = text.find("mass_kg:");
  ASSERT_NE(mass, std::string::npos);
  text.replace(mass, 8, "mass_kg: -45 #");
  std::ofstream(robot) << text;
  const auto r = runScenario("system-bad-robot", "crack-descent --set robot=" + robot.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(robot.string() + ":"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mass_kg = -45"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("starting '"), std::string::npos) << "services were started:\n" << r.output;
  EXPECT_FALSE(fs::exists(r.dir / "trace.csv"));
}

}  // namespace
