// The reference adhesion controller in whole scenario runs, every service a
// process: crack-descent extended to 25 s, so that the crack has left the upper strip for
// several seconds; standing on the crack where several leaks flood the reservoir together and
// the controller gives the flooding chambers up (deploy/scenarios/crack-upper-strips); and a pocket in a flat wall that no controller can
// seal (deploy/scenarios/hole-under-chamber), checked against an independent steady solve of
// the airflow network (tests/support/steady_airflow.hpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "adhesion_controller.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "launcher_run.hpp"
#include "params_from_robot.hpp"
#include "steady_airflow.hpp"

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

/// The first row at or after t [s].
std::size_t rowAt(const std::vector<double>& t, double t_s) {
  return static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), t_s - 1e-9) - t.begin());
}

/// The reference controller's isolations in a run, reconstructed from the trace: the
/// controller model stepped on the measurements it saw (each row's pressures, F and P_F).
/// Faithful only if its commands, through the valves' dead time and stroke, give the trace's
/// valve positions: max_valve_error says how far they are (0 up to rounding).
struct Isolations {
  int transitions = 0;                     ///< isolated <-> admitted changes, all chambers
  std::array<int, 7> per_chamber{};        ///< the same per chamber
  int isolations = 0;                      ///< the controller's own count
  int flood_isolations = 0;                ///< of these, by step 2b (several leaks flooding the reservoir)
  std::array<bool, 7> ever_isolated{};     ///< per chamber
  double max_valve_error = INFINITY;       ///< best over the dead times tried
  std::vector<std::string> events;         ///< "t chamber isolated|re-admitted"
};

Isolations reconstructIsolations(std::map<std::string, std::vector<double>>& trace, double dt_s) {
  using namespace climbsim::controller;
  const auto robot = climbsim::loadRobotDescription(std::string(CLIMBSIM_ROOT) + "/deploy/robots/cromsci.yaml");
  const AdhesionController controller(adhesionControllerParamsFromRobot(robot, climbsim::computeGeometry(robot)));
  auto state = controller.initialState();
  const std::size_t n = trace.at("t_s").size();
  const auto dt_ns = static_cast<std::int64_t>(std::llround(dt_s * 1e9));
  Isolations out;
  constexpr int kValveCount = 7;  // the default robot's chambers
  std::vector<std::vector<double>> commands;
  auto previous = state.isolated;
  for (std::size_t k = 0; k < n; ++k) {
    AdhesionMeasurement m;
    m.pressure_pa.resize(kValveCount + 1);
    for (int i = 0; i < kValveCount; ++i) m.pressure_pa[i] = trace.at("p" + std::to_string(i + 1) + "_pa")[k];
    m.pressure_pa[kValveCount] = trace.at("pr_pa")[k];
    m.downforce_n = trace.at("downforce_n")[k];
    m.p_RobotPF_m = {trace.at("pf_x_m")[k], trace.at("pf_y_m")[k]};
    commands.push_back(controller.step(state, m, static_cast<std::int64_t>(k) * dt_ns, dt_ns).valve_opening);
    for (int i = 0; i < kValveCount; ++i) {
      out.ever_isolated[i] = out.ever_isolated[i] || state.isolated[i];
      if (state.isolated[i] != previous[i]) {
        ++out.transitions;
        ++out.per_chamber[i];
        out.events.push_back(std::to_string(trace.at("t_s")[k]) + " chamber " + std::to_string(i + 1) +
                             (state.isolated[i] ? " isolated" : " re-admitted"));
      }
    }
    previous = state.isolated;
  }
  out.isolations = state.isolation_count;
  out.flood_isolations = state.flood_isolation_count;
  // The valves: the command after a dead time of d steps, then at most dt / stroke per step.
  const double max_move = dt_s / robot.valves.full_stroke_s;
  for (std::size_t d = 0; d <= 8; ++d) {
    std::array<double, kValveCount> position{};
    double worst = 0.0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      for (int i = 0; i < kValveCount; ++i) {
        const double command = k >= d ? commands[k - d][i] : 0.0;
        position[i] += std::clamp(command - position[i], -max_move, max_move);
        worst = std::max(worst, std::abs(position[i] - trace.at("valve" + std::to_string(i + 1))[k + 1]));
      }
    }
    out.max_valve_error = std::min(out.max_valve_error, worst);
  }
  return out;
}

/// The events of `isolations` in one line (for failure messages).
std::string eventsText(const Isolations& isolations) {
  std::string events;
  for (const auto& e : isolations.events) events += e + "; ";
  return events;
}

/// reconstructIsolations at the scenarios' 5 ms step, its events kept as the test's
/// "isolation_events" property (they say what the controller did when a check fails).
Isolations recordedIsolations(std::map<std::string, std::vector<double>>& trace) {
  auto isolations = reconstructIsolations(trace, 0.005);
  ::testing::Test::RecordProperty("isolation_events", eventsText(isolations));
  return isolations;
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
  double f_min = INFINITY, f_max = 0.0, t_max = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (f[k] > f_max) {
      f_max = f[k];
      t_max = t[k];
    }
    if (t[k] > 2.0) f_min = std::min(f_min, f[k]);  // after the hold
  }
  RecordProperty("f_min_after_hold_n", std::to_string(f_min));
  RecordProperty("f_max_n", std::to_string(f_max) + " at " + std::to_string(t_max) + " s");
  EXPECT_GT(f_min, 1.5 * kGripN);
  // Never more than 25 % over the set-point, the whole run long. The hardest moment is 19.55 s:
  // the crack leaves chamber 4's outer strip while chamber 4 is isolated and under a re-seal
  // probe; the chamber and its neighbours go deeper before any command can act (5 ms sample +
  // 20 ms command delay). With the small probe that stays under 1.2 F*
  // (docs/controllers.md#the-reference-controller, services/controller/model/adhesion_controller.hpp).
  EXPECT_LT(f_max, 1.25 * kSetPointN);
  // The controller's isolations, reconstructed from the trace (checked against the valve
  // positions): chamber 1 when the crack reaches its strip (4.8 s), then the chambers the crack
  // passes under, each isolated at most once and re-admitted at most once. No isolate/re-admit
  // cycle.
  const auto isolations = recordedIsolations(trace);
  const std::string events = eventsText(isolations);
  ASSERT_LT(isolations.max_valve_error, 1e-9) << "the reconstruction does not give the trace's valves";
  EXPECT_GE(isolations.isolations, 1) << events;
  for (int c = 0; c < 7; ++c) EXPECT_LE(isolations.per_chamber[c], 2) << "chamber " << c + 1 << ": " << events;
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"fell\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"slid\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"adhesion_failed\": false"), std::string::npos) << summary;
}

// Standing with the crack under the upper strips (deploy/scenarios/crack-upper-strips.yaml):
// each of chambers 3, 4 and 5 leaks about one valve area and together they flood the reservoir.
// The controller gives them up (step 2b: the reservoir's flow balance predicts more downforce
// without them), holds F well above what keeping them all could give (the oracle: a steady solve
// of the airflow network with the trace's leak areas and every valve fully open) and far above
// what the wheels need, and returns to the set-point off the crack without a wound-up overshoot.
TEST(AdhesionScenarios, StandingOnTheCrackUnderTheUpperStripsGivesUpTheFloodingChambersAndRecovers) {
  const auto run = runScenario("system-crack-upper-strips", "crack-upper-strips");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto trace = readTrace(run.dir / "trace.csv");
  const auto& t = trace["t_s"];
  const auto& f = trace["downforce_n"];
  ASSERT_EQ(t.size(), 4800u);
  double f_min_on_crack = INFINITY, f_max_on_crack = 0.0, f_min_after = INFINITY, f_max_after = 0.0, t_max = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] > 6.0 && t[k] < 12.0) {  // standing on the crack, the flooding chambers given up
      f_min_on_crack = std::min(f_min_on_crack, f[k]);
      f_max_on_crack = std::max(f_max_on_crack, f[k]);
    }
    if (t[k] > 2.0) {
      f_min_after = std::min(f_min_after, f[k]);
      if (f[k] > f_max_after) {
        f_max_after = f[k];
        t_max = t[k];
      }
    }
  }
  RecordProperty("f_on_crack_n", std::to_string(f_min_on_crack) + ".." + std::to_string(f_max_on_crack));
  RecordProperty("f_min_after_hold_n", std::to_string(f_min_after));
  RecordProperty("f_max_after_hold_n", std::to_string(f_max_after) + " at " + std::to_string(t_max) + " s");
  const auto robot = climbsim::loadRobotDescription(std::string(CLIMBSIM_ROOT) + "/deploy/robots/cromsci.yaml");
  const auto geometry = climbsim::computeGeometry(robot);
  const auto params = climbsim::thermo::thermoParamsFromRobot(robot, geometry);
  const auto names = climbsim::segmentNames(geometry);
  {
    // The oracle: the most F that keeping every chamber can give, with the leak areas at 9 s.
    const std::size_t row = rowAt(t, 9.0);
    std::vector<double> leak;
    for (const auto& name : names) leak.push_back(trace.at("leak_area_m2_" + name).at(row));
    bool converged = false;
    const double f_keep = climbsim::thermo::testing::steadyDownforce(
        params, climbsim::thermo::testing::steadyPressures(params, leak, climbsim::thermo::testing::uniformOpenings(1.0),
                                                           &converged));
    ASSERT_TRUE(converged);
    RecordProperty("f_keep_all_steady_n", std::to_string(f_keep));
    EXPECT_GT(f_min_on_crack, 1.1 * f_keep) << "giving the flooding chambers up pays";
  }
  EXPECT_LT(f_max_on_crack, kSetPointN);         // below the set-point: P_F balance and the demand cap
  EXPECT_GT(f_min_on_crack, 2.5 * kGripN);       // with a wide margin over what the wheels need
  EXPECT_GT(f_min_after, 1.5 * kGripN);
  // The isolations, reconstructed from the trace (checked against the valve positions): only the
  // leaking chambers 3, 4 and 5 are given up, step 2b among them, each once and re-admitted once
  // off the crack (no cascade, no cycle).
  const auto isolations = recordedIsolations(trace);
  const std::string events = eventsText(isolations);
  ASSERT_LT(isolations.max_valve_error, 1e-9) << "the reconstruction does not give the trace's valves";
  EXPECT_GE(isolations.flood_isolations, 1) << events;
  for (int c : {2, 3, 4}) EXPECT_TRUE(isolations.ever_isolated[c]) << "chamber " << c + 1 << ": " << events;
  for (int c : {0, 1, 5, 6}) EXPECT_FALSE(isolations.ever_isolated[c]) << "chamber " << c + 1 << ": " << events;
  for (int c = 0; c < 7; ++c) EXPECT_LE(isolations.per_chamber[c], 2) << "chamber " << c + 1 << ": " << events;
  // Never over 1.25 F* after the hold, as on crack-descent (measured +12.9 % at 13.99 s). The peak
  // comes after the crack has left the upper strips (about 13.5 s): chambers 3, 4 and 5, given up,
  // re-seal through their walls from their neighbours within tens of milliseconds, before any
  // command can act, and are re-admitted while the reservoir, at 17 kPa with four chambers
  // drawing, pulls them to their targets. The demand cap while chambers are given up (1.2 F*,
  // step 3) keeps the neighbours from being wound up deep: with the 1.5 F* of a single leak the
  // peak is +27.5 %.
  EXPECT_LT(f_max_after, 1.25 * kSetPointN);
  EXPECT_NEAR(f.back(), kSetPointN, 0.02 * kSetPointN);
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"adhesion_failed\": false"), std::string::npos) << summary;
}

// A pocket 60 x 60 mm, 40 mm deep, in a flat wall (deploy/scenes/hole-under-chamber.xml): the
// robot stops with it across the outer strip of chamber 1, about 22 cm² open to the ambient,
// five times the fully open valve's 4.2 cm²; from 12 s it drives on until the pocket lies
// inside chamber 1. The oracle is a separate steady solve of the airflow network (orifice law
// typed in again, none of the thermo model's code) with the leak areas and valve positions of
// the trace.
TEST(AdhesionScenarios, APocketNoControllerCanSealIsIsolatedTheOthersHoldTheSetPointAsASteadySolveSays) {
  const auto run = runScenario("system-hole-under-chamber", "hole-under-chamber");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto trace = readTrace(run.dir / "trace.csv");
  const auto& t = trace["t_s"];
  const auto& f = trace["downforce_n"];
  ASSERT_EQ(t.size(), 3600u);

  const auto robot = climbsim::loadRobotDescription(std::string(CLIMBSIM_ROOT) + "/deploy/robots/cromsci.yaml");
  const auto geometry = climbsim::computeGeometry(robot);
  const auto params = climbsim::thermo::thermoParamsFromRobot(robot, geometry);
  const auto names = climbsim::segmentNames(geometry);
  const double p_o = robot.gas.ambient_pressure_pa;
  const auto suction = [&](int chamber, std::size_t k) {
    return p_o - trace.at("p" + std::to_string(chamber) + "_pa").at(k);
  };
  const auto& valve1 = trace.at("valve1");
  const auto& leak1 = trace.at("leak_area_m2_outer1");
  ASSERT_EQ(leak1.size(), t.size()) << "no leak column for chamber 1's outer strip";
  const double valve_area_m2 = robot.valves.max_area_m2 * robot.valves.discharge_coefficient;

  // Standing on the pocket (6..12 s): chamber 1's outer strip leaks several valve areas.
  const std::size_t stand0 = rowAt(t, 6.0), stand1 = rowAt(t, 12.0);
  for (std::size_t k = stand0; k < stand1; ++k) ASSERT_GT(leak1[k], 4.0 * valve_area_m2) << "t = " << t[k];

  // The controller isolates chamber 1: its valve is closed, apart from short probes at the
  // probe opening, while the pocket is under the strip.
  double closed_s = 0.0, valve1_max = 0.0;
  for (std::size_t k = stand0; k < stand1; ++k) {
    if (valve1[k] < 0.01) closed_s += 0.005;
    valve1_max = std::max(valve1_max, valve1[k]);
  }
  RecordProperty("valve1_closed_share", std::to_string(closed_s / 6.0));
  EXPECT_GT(closed_s, 0.8 * 6.0);
  EXPECT_LE(valve1_max, 0.02 + 1e-9) << "only the probes (opening 0.02) may open it";

  // Graceful: after the hold F stays above m g / mu with margin, even while the pocket
  // floods the reservoir before the isolation, and the robot does not slide.
  double f_min = INFINITY, f_max = 0.0;
  for (std::size_t k = rowAt(t, 2.0); k < t.size(); ++k) {
    f_min = std::min(f_min, f[k]);
    f_max = std::max(f_max, f[k]);
  }
  RecordProperty("f_min_after_hold_n", std::to_string(f_min));
  RecordProperty("f_max_n", std::to_string(f_max));
  EXPECT_GT(f_min, 2.0 * kGripN);
  EXPECT_LT(f_max, 1.25 * kSetPointN);
  const std::string summary = readFile(run.dir / "summary.json");
  EXPECT_NE(summary.find("\"slid\": false"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"adhesion_failed\": false"), std::string::npos) << summary;

  // The other six hold the set-point: F at F*, each of them with real suction.
  const std::size_t k = rowAt(t, 11.0);  // no probe from 9 to 11 s, the robot stands
  for (std::size_t j = rowAt(t, 9.0); j <= k; ++j) ASSERT_EQ(valve1[j], 0.0) << "t = " << t[j];
  EXPECT_NEAR(f[k], kSetPointN, 0.02 * kSetPointN);
  for (int c = 2; c <= 7; ++c) EXPECT_GT(suction(c, k), 2000.0) << "chamber " << c;
  EXPECT_LT(suction(1, k), 100.0) << "chamber 1 is open to the ambient";

  // The oracle: the steady state of the airflow network with the trace's leaks and valves.
  std::vector<double> leak_m2;
  for (const auto& name : names) leak_m2.push_back(trace.at("leak_area_m2_" + name).at(k));
  climbsim::thermo::testing::Openings opening{};
  for (int c = 0; c < 7; ++c) opening[c] = trace.at("valve" + std::to_string(c + 1)).at(k);
  bool converged = false;
  const auto steady = climbsim::thermo::testing::steadyPressures(params, leak_m2, opening, &converged);
  ASSERT_TRUE(converged);
  const double f_steady = climbsim::thermo::testing::steadyDownforce(params, steady);
  RecordProperty("f_steady_solve_n", std::to_string(f_steady));
  EXPECT_NEAR(f[k], f_steady, 0.01 * f_steady);
  for (int c = 0; c < 7; ++c) {
    EXPECT_NEAR(suction(c + 1, k), p_o - steady[c], 0.02 * (p_o - steady[c]) + 20.0) << "chamber " << c + 1;
  }
  // In the solve too chamber 1 sits at the ambient and the other six give F*: the set-point
  // is held without chamber 1.
  EXPECT_LT(p_o - steady[0], 0.01 * (p_o - steady[params.reservoir()]));
  EXPECT_NEAR(f_steady, kSetPointN, 0.02 * kSetPointN);

  // No controller can compensate the pocket: with every valve fully open chamber 1 holds at
  // most a few per cent of the reservoir's suction (1 / (1 + lambda²), lambda ~ 5), and opening
  // chamber 1's valve alone floods the reservoir: the others' valves as they are then give far
  // less than F*.
  const auto all_open = climbsim::thermo::testing::steadyPressures(
      params, leak_m2, climbsim::thermo::testing::uniformOpenings(1.0));
  const double s1_best = p_o - all_open[0];
  RecordProperty("chamber1_best_suction_share", std::to_string(s1_best / (p_o - all_open[params.reservoir()])));
  EXPECT_LT(s1_best, 0.1 * (p_o - all_open[params.reservoir()]));
  auto leaking_open = opening;
  leaking_open[0] = 1.0;
  const double f_leaking_open = climbsim::thermo::testing::steadyDownforce(
      params, climbsim::thermo::testing::steadyPressures(params, leak_m2, leaking_open));
  RecordProperty("f_steady_valve1_open_n", std::to_string(f_leaking_open));
  EXPECT_LT(f_leaking_open, 0.8 * f_steady);

  // The pocket has passed (inside chamber 1, away from every strip, from about 13 s): chamber
  // 1 is re-admitted, pulls again, and F is back at F*.
  const std::size_t end = t.size() - 1;
  EXPECT_LT(leak1[end], 2.0 * leak1[rowAt(t, 1.0)]);
  double valve1_after = 0.0;
  for (std::size_t j = rowAt(t, 13.5); j < t.size(); ++j) valve1_after = std::max(valve1_after, valve1[j]);
  EXPECT_GT(valve1_after, 0.0) << "chamber 1 is never re-admitted";
  EXPECT_GT(suction(1, end), 0.5 * suction(7, end));
  EXPECT_NEAR(f[end], kSetPointN, 0.02 * kSetPointN);
}

}  // namespace

