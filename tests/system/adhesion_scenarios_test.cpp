// The reference adhesion controller in whole scenario runs (issue 16, item 4), every service a
// process: crack-descent extended to 25 s, so that the crack has left the upper strip for
// several seconds, and standing on the crack where the controller cannot make up the leak
// (deploy/scenarios/crack-upper-strips). The leak no controller can compensate is shown in the
// closed loop with the thermo model (tests/unit/controller, AdhesionControllerIsolation).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "launcher_run.hpp"

namespace {

using namespace climbsim::system_test;

/// The columns of trace.csv by name.
std::map<std::string, std::vector<double>> readTrace(const fs::path& path) {
  std::istringstream lines(readFile(path));
  std::string line;
  std::getline(lines, line);
  std::vector<std::string> names;
  {
    std::istringstream header(line);
    std::string name;
    while (std::getline(header, name, ',')) names.push_back(name);
  }
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    std::string cell;
    for (std::size_t c = 0; c < names.size() && std::getline(cells, cell, ','); ++c) {
      columns[names[c]].push_back(std::strtod(cell.c_str(), nullptr));
    }
  }
  return columns;
}

/// m g / mu of the default robot: the least downforce at which the wheels hold it [N].
constexpr double kGripN = 45.0 * 9.81 / 0.7;
constexpr double kSetPointN = 2200.0;

TEST(AdhesionScenarios, CrackDescentFor25sHoldsWithMarginDoesNotOvershootAndDoesNotSlide) {
  const auto run = runScenario("system-crack-descent-25s", "crack-descent --set duration_s=25");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto trace = readTrace(run.dir / "trace.csv");
  const auto& t = trace["t_s"];
  const auto& f = trace["downforce_n"];
  ASSERT_EQ(t.size(), 5000u);
  double f_min = INFINITY, f_max = 0.0, over_s = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    f_max = std::max(f_max, f[k]);
    if (t[k] > 2.0) f_min = std::min(f_min, f[k]);  // after the hold
    if (f[k] > 1.25 * kSetPointN) over_s += 0.005;
  }
  RecordProperty("f_min_after_hold_n", std::to_string(f_min));
  RecordProperty("f_max_n", std::to_string(f_max));
  RecordProperty("over_25_percent_s", std::to_string(over_s));
  EXPECT_GT(f_min, 1.5 * kGripN);
  // Never more than 25 % over the set-point, except for the instant the crack leaves the upper
  // strip: the leak stops within 10 ms and the chambers that made up for it are deeper than
  // their targets before any valve can move (20 ms command delay): a spike of about 50 ms that
  // no valve controller can prevent (README "Controller and recorder").
  EXPECT_LE(over_s, 0.1 + 1e-9);
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"fell\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"slid\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"adhesion_failed\": false"), std::string::npos) << summary;
}

// Standing with the crack under the upper strips (deploy/scenarios/crack-upper-strips.yaml):
// the leaks flood the reservoir and F stays below the set-point; the controller degrades, it
// does not collapse, and returns to the set-point off the crack without a wound-up overshoot.
TEST(AdhesionScenarios, StandingOnTheCrackUnderTheUpperStripsDegradesGracefullyAndRecovers) {
  const auto run = runScenario("system-crack-upper-strips", "crack-upper-strips");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto trace = readTrace(run.dir / "trace.csv");
  const auto& t = trace["t_s"];
  const auto& f = trace["downforce_n"];
  ASSERT_EQ(t.size(), 4800u);
  double f_min_on_crack = INFINITY, f_max_on_crack = 0.0, f_min_after = INFINITY, over_s = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] > 4.0 && t[k] < 12.0) {  // standing on the crack, vacuum built
      f_min_on_crack = std::min(f_min_on_crack, f[k]);
      f_max_on_crack = std::max(f_max_on_crack, f[k]);
    }
    if (t[k] > 2.0) f_min_after = std::min(f_min_after, f[k]);
    if (f[k] > 1.25 * kSetPointN) over_s += 0.005;
  }
  RecordProperty("f_on_crack_n", std::to_string(f_min_on_crack) + ".." + std::to_string(f_max_on_crack));
  EXPECT_LT(f_max_on_crack, kSetPointN);         // below the set-point: not compensated
  EXPECT_GT(f_min_on_crack, 1.5 * kGripN);       // but with margin over what the wheels need
  EXPECT_GT(f_min_after, kGripN);
  // Nothing wound up while it could not follow: over 1.25 F* only for the spike when the leak
  // stops (as in crack-descent).
  EXPECT_LE(over_s, 0.1 + 1e-9);
  EXPECT_NEAR(f.back(), kSetPointN, 0.02 * kSetPointN);
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"adhesion_failed\": false"), std::string::npos) << summary;
}

}  // namespace
