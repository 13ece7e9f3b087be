// The thermo model on every shipped robot (deploy/robots), configured as climbsim-thermo
// configures it (configureThermo), checked against what is computed here independently:
// the single chamber's steady pressure by bisection of engine curve = leak, downforce and its
// point of action from the outline polygons sampled on a fine grid, the air-mass balance,
// the grid robot's symmetry, and the venting when the engines stop
// (docs/design.md#airflow-and-downforce).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "thermo/configure.hpp"
#include "thermo_model.hpp"
#include "thermo_translate.hpp"

namespace climbsim::thermo {
namespace {

constexpr std::int64_t kPeriodNs = 5'000'000;
constexpr double kPi = 3.14159265358979323846;
const char* const kShippedRobots[] = {"cromsci", "single-chamber", "grid-2x2", "ring-12"};

struct Robot {
  ScenarioAndRobot run;
  ThermoSetup setup;
};

Robot loadRobot(const std::string& name) {
  Robot r;
  r.run = loadScenarioAndRobot("", {}, std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml");
  r.setup = configureThermo(r.run);
  return r;
}

/// Basic leaks, every valve at `opening`, every engine on at full speed.
ThermoInputs suction(const ThermoSetup& setup, double opening) {
  ThermoInputs in;
  in.leak_area_m2 = setup.basic_leak_area_m2;
  in.valve_command.assign(static_cast<std::size_t>(setup.params.valveCount()), opening);
  in.engines.assign(setup.params.engines.size(), EngineCommand{true, 1.0});
  return in;
}

ThermoOutputs runFor(const ThermoModel& model, ThermoState& state, const ThermoInputs& in, double seconds) {
  ThermoOutputs out;
  const auto steps = std::lround(seconds / (static_cast<double>(kPeriodNs) * 1e-9));
  for (long k = 0; k < steps; ++k) out = model.step(state, in, state.t_ns, kPeriodNs);
  return out;
}

TEST(ThermoRobots, EveryShippedRobotConfiguresWithItsCounts) {
  for (const char* name : kShippedRobots) {
    const Robot r = loadRobot(name);
    const ThermoParams& p = r.setup.params;
    const RobotGeometry& g = r.run.geometry;
    EXPECT_EQ(p.chamberCount(), g.chamberCount()) << name;
    EXPECT_EQ(p.has_reservoir, g.has_reservoir) << name;
    EXPECT_EQ(p.volumeCount(), g.volumeCount()) << name;
    EXPECT_EQ(p.valveCount(), g.has_reservoir ? g.chamberCount() : 0) << name;
    EXPECT_EQ(p.engines.size(), static_cast<std::size_t>(r.run.robot.engines.count)) << name;
    EXPECT_EQ(p.segments.size(), g.segments.size()) << name;
    const ThermoNode node(r.setup.params, r.setup.segment_names, r.setup.basic_leak_area_m2);
    const ThermoOutputs initial = node.initialOutputs();
    EXPECT_EQ(initial.pressure_pa.size(), static_cast<std::size_t>(g.volumeCount())) << name;
    EXPECT_EQ(initial.valve_opening.size(), static_cast<std::size_t>(p.valveCount())) << name;
    const auto sample = chamberStateToIdl(initial);
    EXPECT_EQ(sample.pressure_pa().size(), static_cast<std::size_t>(g.volumeCount())) << name;
  }
}

// --- (1) a single chamber's steady pressure: engine curve = leak, by bisection ---------------

TEST(ThermoRobots, SingleChamberSettlesWhereEngineCurveMeetsTheLeak) {
  const Robot r = loadRobot("single-chamber");
  const RobotDescription& d = r.run.robot;
  ASSERT_FALSE(d.reservoir.present);
  ASSERT_EQ(d.engines.count, 1);
  // The leak: the strip's centre line (a circle of chambers.diameter_m) times the basic gap.
  const double leak_m2 = kPi * d.chambers.diameter_m * d.sealing.basic_gap_m;
  double model_leak_m2 = 0.0;
  for (double a : r.setup.basic_leak_area_m2) model_leak_m2 += a;
  ASSERT_NEAR(model_leak_m2, leak_m2, 1e-4 * leak_m2) << "the robot's sealing is its one outer strip";

  const double p_o = d.gas.ambient_pressure_pa;
  const double rt = d.gas.r_air_jpkgk * d.gas.temperature_k;
  // Engine at full speed on the chamber: mdot = p / (R T) Q_max (1 - (p_o - p) / dp_max).
  const auto engine = [&](double p) { return p / rt * d.engines.flow_max_m3ps * (1.0 - (p_o - p) / d.engines.dp_max_pa); };
  // Orifice law above the laminar threshold: mdot = A sqrt(2 rho (p_o - p)).
  const auto leak = [&](double p) { return leak_m2 * std::sqrt(2.0 * d.gas.rho_kgpm3 * (p_o - p)); };
  double lo = p_o - d.engines.dp_max_pa, hi = p_o;  // engine - leak: < 0 at lo, > 0 at hi
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (engine(mid) - leak(mid) > 0.0 ? hi : lo) = mid;
  }
  const double p_root = 0.5 * (lo + hi);
  ASSERT_GT(p_o - p_root, 100.0 * r.setup.params.laminar_threshold_pa) << "the root lies on the turbulent branch";

  const ThermoModel model(r.setup.params);
  ThermoState state = model.initialState();
  const ThermoOutputs out = runFor(model, state, suction(r.setup, 0.0), 20.0);
  ASSERT_EQ(out.pressure_pa.size(), 1u);
  EXPECT_NEAR(p_o - out.pressure_pa[0], p_o - p_root, 1e-3 * (p_o - p_root));
  EXPECT_NEAR(out.downforce_n, (p_o - p_root) * r.setup.params.chamber_area_m2[0], 1e-3 * out.downforce_n);
  RecordProperty("suction_root_pa", std::to_string(p_o - p_root));
}

// --- (2) downforce and its point of action from the outlines ------------------------------

bool inside(const std::vector<RobotGeometry::Point>& polygon, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if ((a.y_m > y) != (b.y_m > y) && x < (b.x_m - a.x_m) * (y - a.y_m) / (b.y_m - a.y_m) + a.x_m) in = !in;
  }
  return in;
}

struct Moments {
  double area_m2 = 0.0;
  double x_m = 0.0;  ///< centroid
  double y_m = 0.0;
};

/// Area and centroid of a polygon by sampling its bounding box at cell midpoints.
Moments sampled(const std::vector<RobotGeometry::Point>& polygon, int cells) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto& p : polygon) {
    x0 = std::min(x0, p.x_m), x1 = std::max(x1, p.x_m), y0 = std::min(y0, p.y_m), y1 = std::max(y1, p.y_m);
  }
  const double hx = (x1 - x0) / cells, hy = (y1 - y0) / cells;
  double n = 0.0, sx = 0.0, sy = 0.0;
  for (int i = 0; i < cells; ++i) {
    const double x = x0 + (i + 0.5) * hx;
    for (int j = 0; j < cells; ++j) {
      const double y = y0 + (j + 0.5) * hy;
      if (inside(polygon, x, y)) n += 1.0, sx += x, sy += y;
    }
  }
  return {n * hx * hy, sx / n, sy / n};
}

TEST(ThermoRobots, DownforceAndPointOfActionFollowTheOutlines) {
  for (const char* name : {"grid-2x2", "ring-12"}) {
    const Robot r = loadRobot(name);
    const ThermoModel model(r.setup.params);
    ThermoState state = model.initialState();
    const double p_o = r.setup.params.gas.ambient_pressure_pa;
    const auto& chambers = r.run.geometry.chambers;
    double force = 0.0, mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < chambers.size(); ++i) {
      const double suction_pa = 1000.0 + 700.0 * static_cast<double>(i * i % 5) + 90.0 * static_cast<double>(i);
      state.pressure_pa[i] = p_o - suction_pa;
      const Moments m = sampled(chambers[i].outline_Robot, 700);
      force += suction_pa * m.area_m2;
      mx += m.x_m * suction_pa * m.area_m2;
      my += m.y_m * suction_pa * m.area_m2;
    }
    const ThermoOutputs out = model.outputsOf(state, r.setup.basic_leak_area_m2);
    EXPECT_NEAR(out.downforce_n, force, 2e-3 * force) << name;
    EXPECT_NEAR(out.suction_moment_nm[0], mx, 2e-3 * std::abs(force)) << name;
    EXPECT_NEAR(out.suction_moment_nm[1], my, 2e-3 * std::abs(force)) << name;
    EXPECT_NEAR(out.p_RobotPF_m[0], mx / force, 1e-3) << name;
    EXPECT_NEAR(out.p_RobotPF_m[1], my / force, 1e-3) << name;
    EXPECT_GT(std::hypot(mx / force, my / force), 5e-3) << name << ": the pressures are uneven, P_F is off-centre";
  }
}

// --- (3) mass balance on every robot ------------------------------------------------------

TEST(ThermoRobots, AirMassBalanceHoldsOnEveryRobotUnderChangingValvesAndLeaks) {
  for (const char* name : kShippedRobots) {
    const Robot r = loadRobot(name);
    const ThermoModel model(r.setup.params);
    ThermoState state = model.initialState();
    ThermoInputs in = suction(r.setup, 0.5);
    const ThermoOutputs first = model.step(state, in, state.t_ns, kPeriodNs);
    const double balance0 = first.air_mass_kg - first.ambient_inflow_kg + first.engine_outflow_kg;
    ThermoOutputs out;
    for (int k = 0; k < 600; ++k) {
      for (std::size_t c = 0; c < in.valve_command.size(); ++c) {
        in.valve_command[c] = 0.5 + 0.5 * std::sin(0.05 * k + static_cast<double>(c));
      }
      for (std::size_t s = 0; s < in.leak_area_m2.size(); ++s) {
        in.leak_area_m2[s] = r.setup.basic_leak_area_m2[s] * (1.0 + 4.0 * std::pow(std::sin(0.02 * k + s), 2));
      }
      for (std::size_t e = 0; e < in.engines.size(); ++e) in.engines[e].speed = 0.6 + 0.4 * std::cos(0.03 * k + e);
      out = model.step(state, in, state.t_ns, kPeriodNs);
    }
    const double stored = out.air_mass_kg - first.air_mass_kg;
    ASSERT_GT(std::abs(stored), 1e-5) << name << ": the robot was evacuated";
    ASSERT_GT(out.engine_outflow_kg - first.engine_outflow_kg, 1e-3) << name;
    const double balance = out.air_mass_kg - out.ambient_inflow_kg + out.engine_outflow_kg;
    EXPECT_LE(std::abs(balance - balance0), 1e-9 * std::abs(stored)) << name;
  }
}

// --- (4) the grid robot's symmetry ----------------------------------------------------------

TEST(ThermoRobots, GridCellsGiveSymmetricPressuresOnAFlatWall) {
  const Robot r = loadRobot("grid-2x2");
  ASSERT_EQ(r.setup.params.chamberCount(), 4);
  // Each cell's outer strip has the same length: equal leak areas by symmetry.
  std::vector<double> outer_leak(4, 0.0);
  for (std::size_t s = 0; s < r.setup.params.segments.size(); ++s) {
    const auto& seg = r.setup.params.segments[s];
    if (seg.volume_b == kAmbient) outer_leak[static_cast<std::size_t>(seg.volume_a)] += r.setup.basic_leak_area_m2[s];
  }
  for (int c = 1; c < 4; ++c) EXPECT_NEAR(outer_leak[c], outer_leak[0], 1e-12 * outer_leak[0]) << "cell " << c + 1;

  const ThermoModel model(r.setup.params);
  ThermoState state = model.initialState();
  const ThermoOutputs out = runFor(model, state, suction(r.setup, 1.0), 15.0);
  const double p_o = r.setup.params.gas.ambient_pressure_pa;
  ASSERT_GT(p_o - out.pressure_pa[0], 1000.0);
  for (int c = 1; c < 4; ++c) EXPECT_NEAR(out.pressure_pa[c], out.pressure_pa[0], 1e-3) << "cell " << c + 1;
  EXPECT_NEAR(out.p_RobotPF_m[0], 0.0, 1e-6);
  EXPECT_NEAR(out.p_RobotPF_m[1], 0.0, 1e-6);
}

// --- (5) engines stopped: back to ambient ---------------------------------------------------

TEST(ThermoRobots, StoppedEnginesLetEveryRobotReturnToAmbient) {
  for (const char* name : kShippedRobots) {
    const Robot r = loadRobot(name);
    const ThermoModel model(r.setup.params);
    ThermoState state = model.initialState();
    ThermoInputs in = suction(r.setup, 1.0);
    const ThermoOutputs held = runFor(model, state, in, 5.0);
    ASSERT_GT(held.downforce_n, 100.0) << name;
    for (auto& e : in.engines) e.on = false;
    const ThermoOutputs out = runFor(model, state, in, 30.0);
    const double p_o = r.setup.params.gas.ambient_pressure_pa;
    for (std::size_t v = 0; v < out.pressure_pa.size(); ++v) {
      EXPECT_NEAR(out.pressure_pa[v], p_o, 0.5) << name << " volume " << v + 1;
    }
    EXPECT_NEAR(out.downforce_n, 0.0, 1.0) << name;
  }
}

// --- commands sized for another robot -------------------------------------------------------

TEST(ThermoRobots, WithoutAReservoirValveCommandsAreEmptyAndOthersAreDropped) {
  const Robot r = loadRobot("single-chamber");
  ThermoNode node(r.setup.params, r.setup.segment_names, r.setup.basic_leak_area_m2);
  auto set_point_only = valveCommandToIdl({});
  set_point_only.downforce_setpoint_n(500.0);
  auto one_valve = valveCommandToIdl({0.5});
  const auto engines = engineCommandToIdl({EngineCommand{true, 1.0}});
  const ThermoOutputs out = node.step(0, kPeriodNs, {}, {set_point_only, one_valve}, {engines});
  EXPECT_EQ(node.droppedValveCommands(), 1u);
  EXPECT_EQ(node.downforceSetpoint(), 500.0);
  EXPECT_TRUE(out.valve_opening.empty());
  EXPECT_EQ(out.pressure_pa.size(), 1u);
  ThermoInputs wrong = suction(r.setup, 0.0);
  wrong.valve_command = {0.5};
  EXPECT_EQ(validateInputs(r.setup.params, wrong),
            "thermo input: valve_command has 1 entries, the robot has 0 valves (no reservoir: none)");
  ThermoState state = node.model().initialState();
  EXPECT_THROW(node.model().step(state, wrong, 0, kPeriodNs), InvalidInputError);
}

TEST(ThermoRobots, FaultsAreCheckedAgainstTheRobot) {
  Scenario::Fault stuck;
  stuck.kind = Scenario::FaultKind::kValveStuck;
  stuck.chamber = 13;
  stuck.opening = 0.5;
  const Robot ring = loadRobot("ring-12");
  EXPECT_EQ(plantFaultsFromScenario({stuck}, "s.yaml", ring.setup.params).size(), 1u);  // the centre chamber
  stuck.chamber = 14;
  EXPECT_THROW(plantFaultsFromScenario({stuck}, "s.yaml", ring.setup.params), ConfigError);
  stuck.chamber = 1;
  const Robot single = loadRobot("single-chamber");
  try {
    plantFaultsFromScenario({stuck}, "s.yaml", single.setup.params);
    FAIL() << "a stuck valve on a robot without valves";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml: faults[0].kind = valve_stuck: the robot has no valves"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace climbsim::thermo
