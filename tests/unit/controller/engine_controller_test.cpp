// The engine law (robots without a reservoir) in a closed loop with the real thermo model (no
// DDS), the controller seeing the plant's outputs of the previous exchange period; steady states
// checked against the engine curve and the leak solved independently (bisection, no
// integrator, none of the thermo model's code).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "command_model.hpp"
#include "engine_controller.hpp"
#include "params_from_robot.hpp"
#include "thermo_model.hpp"

namespace climbsim::controller {
namespace {

constexpr std::int64_t kPeriodNs = 5'000'000;  // 5 ms exchange period
constexpr double kPeriodS = 5e-3;
constexpr double kPi = 3.14159265358979323846;

std::string shippedRobot(const std::string& name) { return std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml"; }

struct EngineTrace {
  std::vector<double> t_s;
  std::vector<double> downforce_n;
  std::vector<double> command;       ///< engine 1's commanded speed
  std::vector<double> speed;         ///< engine 1's actual speed (thermo)
  std::vector<double> pf_norm_m;     ///< |P_F|
  double min_command = 1.0, max_command = 0.0, min_speed = 1.0, max_speed = 0.0;
  std::vector<double> final_speed;   ///< every engine's actual speed at the end
  std::vector<double> final_suction_pa;

  /// Mean of `v` over the rows with t in [from_s, to_s).
  double mean(const std::vector<double>& v, double from_s, double to_s) const {
    double sum = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < t_s.size(); ++k) {
      if (t_s[k] >= from_s && t_s[k] < to_s) sum += v[k], ++n;
    }
    return sum / n;
  }
  /// The first time from which F stays within `ratio` of f_set to the end [s].
  double settledAt(double f_set, double ratio) const {
    double at = 0.0;
    for (std::size_t k = 0; k < t_s.size(); ++k) {
      if (std::abs(downforce_n[k] - f_set) > ratio * f_set) at = t_s[k];
    }
    return at;
  }
};

/// The engine law on a robot without a reservoir and the thermo model of the same robot.
class EngineLoop {
 public:
  explicit EngineLoop(const std::string& robot_file) {
    robot_ = loadRobotDescription(robot_file);
    geometry_ = computeGeometry(robot_);
    thermo_params_ = thermo::thermoParamsFromRobot(robot_, geometry_);
    params_ = engineControllerParamsFromRobot(robot_, geometry_);
    leak_area_m2_ = thermo::basicLeakAreas(robot_, geometry_);
  }

  EngineControllerParams& params() { return params_; }
  const RobotDescription& robot() const { return robot_; }
  const RobotGeometry& geometry() const { return geometry_; }
  std::vector<double>& leakAreas() { return leak_area_m2_; }

  /// Runs for duration_s; `leak_at(t, leaks)` may change the leak areas on the way.
  EngineTrace run(double duration_s, const std::function<void(double, std::vector<double>&)>& leak_at = {}) {
    thermo::ThermoModel model(thermo_params_);
    const EngineController controller(params_);
    EngineControllerState control = controller.initialState();
    auto state = model.initialState(0);
    thermo::ThermoInputs inputs;
    inputs.leak_area_m2 = leak_area_m2_;
    inputs.engines.assign(thermo_params_.engines.size(), thermo::EngineCommand{false, 1.0});
    AdhesionMeasurement measured;
    measured.pressure_pa.assign(geometry_.chambers.size(), robot_.gas.ambient_pressure_pa);
    EngineTrace trace;
    const long steps = std::lround(duration_s / kPeriodS);
    for (long k = 0; k < steps; ++k) {
      const double t_s = k * kPeriodS;
      if (leak_at) leak_at(t_s, inputs.leak_area_m2);
      const auto speeds = controller.step(control, measured, k * kPeriodNs, kPeriodNs).engine_speed;
      for (std::size_t e = 0; e < speeds.size(); ++e) inputs.engines[e] = thermo::EngineCommand{true, speeds[e]};
      const auto out = model.step(state, inputs, k * kPeriodNs, kPeriodNs);
      measured.pressure_pa = out.pressure_pa;
      measured.downforce_n = out.downforce_n;
      measured.p_RobotPF_m = out.p_RobotPF_m;
      trace.t_s.push_back(t_s + kPeriodS);
      trace.downforce_n.push_back(out.downforce_n);
      trace.command.push_back(speeds[0]);
      trace.speed.push_back(out.engine_speed[0]);
      trace.pf_norm_m.push_back(std::hypot(out.p_RobotPF_m[0], out.p_RobotPF_m[1]));
      for (double s : speeds) trace.min_command = std::min(trace.min_command, s), trace.max_command = std::max(trace.max_command, s);
      for (double s : out.engine_speed) trace.min_speed = std::min(trace.min_speed, s), trace.max_speed = std::max(trace.max_speed, s);
      trace.final_speed = out.engine_speed;
      trace.final_suction_pa.clear();
      for (double p : out.pressure_pa) trace.final_suction_pa.push_back(robot_.gas.ambient_pressure_pa - p);
    }
    return trace;
  }

 private:
  RobotDescription robot_;
  RobotGeometry geometry_;
  thermo::ThermoParams thermo_params_;
  EngineControllerParams params_;
  std::vector<double> leak_area_m2_;
};

/// The single chamber's steady suction [Pa] with its engine at `speed` and a leak of `leak_m2`,
/// typed from the fan curve and the orifice law (docs/design.md#airflow-and-downforce):
///   engine: mdot = p / (R T) Q_max w (1 - (p_o - p) / (dp_max w²)),  leak: A sqrt(2 rho (p_o - p)),
/// their crossing found by bisection.
double steadySuction(const RobotDescription& d, double speed, double leak_m2) {
  const double p_o = d.gas.ambient_pressure_pa;
  const double rt = d.gas.r_air_jpkgk * d.gas.temperature_k;
  const auto engine = [&](double p) {
    return p / rt * d.engines.flow_max_m3ps * speed * (1.0 - (p_o - p) / (d.engines.dp_max_pa * speed * speed));
  };
  const auto leak = [&](double p) { return leak_m2 * std::sqrt(2.0 * d.gas.rho_kgpm3 * (p_o - p)); };
  double lo = p_o - d.engines.dp_max_pa * speed * speed, hi = p_o;  // engine - leak: < 0 at lo, > 0 at hi
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (engine(mid) - leak(mid) > 0.0 ? hi : lo) = mid;
  }
  return p_o - 0.5 * (lo + hi);
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

// --- the single-chamber robot on the flat wall --------------------------------------------

TEST(EngineController, SingleChamberDownforceSettlesAtTheSetPoint) {
  EngineLoop loop(shippedRobot("single-chamber"));
  const double f_set = loop.params().desired_downforce_n;
  ASSERT_EQ(f_set, 700.0);
  const EngineTrace tr = loop.run(10.0);
  const double settled_s = tr.settledAt(f_set, 0.02);
  std::printf("bench: engine-law: single-chamber F* %.0f N: within 2 %% from %.2f s, F 8-10 s %.3f N, speed %.4f\n", f_set,
              settled_s, tr.mean(tr.downforce_n, 8.0, 10.0), tr.final_speed[0]);
  RecordProperty("settled_within_2_percent_s", std::to_string(settled_s));
  EXPECT_LT(settled_s, 3.0);
  EXPECT_NEAR(tr.downforce_n.back(), f_set, 1e-3 * f_set);
  // Independently: the fan curve at the engine's steady speed meets the leak at the set-point's suction.
  const double s_root = steadySuction(loop.robot(), tr.final_speed[0], sum(loop.leakAreas()));
  EXPECT_NEAR(s_root * loop.geometry().chambers[0].area_m2, f_set, 5e-3 * f_set);
  // The engine does not run at full speed: the law holds F* with speed to spare.
  EXPECT_LT(tr.final_speed[0], 0.95);
  EXPECT_GT(tr.final_speed[0], std::sqrt(f_set / loop.geometry().chambers[0].area_m2 / loop.robot().engines.dp_max_pa));
}

TEST(EngineController, EngineSpeedStaysWithinItsLimits) {
  // Reachable (the robot file's set-point) and out of reach (a set-point beyond dp_max A, and a
  // crack under the strip): every command and every actual speed within [0, 1].
  for (const double f_set : {700.0, 5000.0}) {
    EngineLoop loop(shippedRobot("single-chamber"));
    loop.params().desired_downforce_n = f_set;
    const EngineTrace tr = loop.run(8.0, [](double t, std::vector<double>& leak) {
      if (std::abs(t - 4.0) < 1e-9) leak[0] *= 20.0;
    });
    EXPECT_GE(tr.min_command, 0.0) << f_set;
    EXPECT_LE(tr.max_command, 1.0) << f_set;
    EXPECT_GE(tr.min_speed, 0.0) << f_set;
    EXPECT_LE(tr.max_speed, 1.0) << f_set;
    if (f_set > 1000.0) {
      EXPECT_EQ(tr.command.back(), 1.0) << "out of reach: full speed";
    }
  }
}

TEST(EngineController, AHigherSetPointGivesAHigherSteadyEngineSpeed) {
  std::vector<double> speeds;
  for (const double f_set : {300.0, 500.0, 700.0, 900.0, 1100.0}) {
    EngineLoop loop(shippedRobot("single-chamber"));
    loop.params().desired_downforce_n = f_set;
    const EngineTrace tr = loop.run(8.0);
    EXPECT_NEAR(tr.downforce_n.back(), f_set, 2e-3 * f_set) << f_set;
    speeds.push_back(tr.final_speed[0]);
  }
  for (std::size_t k = 1; k < speeds.size(); ++k) EXPECT_GT(speeds[k], speeds[k - 1]) << k;
}

TEST(EngineController, ALeakStepSpeedsTheEngineUpAndTheDownforceComesBack) {
  EngineLoop loop(shippedRobot("single-chamber"));
  const double f_set = loop.params().desired_downforce_n;
  const double basic_m2 = loop.leakAreas()[0];
  const EngineTrace tr = loop.run(12.0, [&](double t, std::vector<double>& leak) {
    if (std::abs(t - 5.0) < 1e-9) leak[0] = 1.5 * basic_m2;  // the strip's gap widens by half at 5 s
  });
  const double before = tr.mean(tr.speed, 4.0, 5.0);
  const double after = tr.mean(tr.speed, 11.0, 12.0);
  std::printf("bench: engine-law: leak x1.5 at 5 s: speed %.4f -> %.4f, least F after it %.1f N, within 2 %% "
              "again from %.2f s, F at 12 s %.2f N\n",
              before, after, *std::min_element(tr.downforce_n.begin() + 1000, tr.downforce_n.end()),
              tr.settledAt(f_set, 0.02), tr.downforce_n.back());
  EXPECT_GT(after, before + 0.02);
  EXPECT_NEAR(tr.downforce_n.back(), f_set, 2e-3 * f_set);
  EXPECT_LT(tr.settledAt(f_set, 0.02), 8.0);
  // Independently: the new speed is where the fan curve meets the wider leak at F*'s suction.
  const double s_root = steadySuction(loop.robot(), tr.final_speed[0], 1.5 * basic_m2);
  EXPECT_NEAR(s_root * loop.geometry().chambers[0].area_m2, f_set, 5e-3 * f_set);
}

// --- several chambers, each on its own engine: shares and tilt balance --------------------

/// A 2 x 2 grid without a reservoir, one engine on each cell (written next to the test's outputs).
std::string gridWithoutReservoir() {
  const std::string text = [] {
    std::ifstream in(shippedRobot("grid-2x2"));
    std::string all, line;
    bool skip = false;
    while (std::getline(in, line)) {
      if (line.rfind("reservoir:", 0) == 0 || line.rfind("valves:", 0) == 0 || line.rfind("engines:", 0) == 0) {
        skip = true;
        continue;
      }
      if (skip && (line.empty() || line[0] == ' ')) continue;
      skip = false;
      all += line + "\n";
    }
    return all + "engines:\n  count: 4\n  dp_max_pa: 22000\n  flow_max_m3ps: 0.030\n  speed_lag_s: 0.5\n"
                 "  chambers: [1, 2, 3, 4]\n";
  }();
  const auto path = std::filesystem::temp_directory_path() / "climbsim-test-grid-engines.yaml";
  std::ofstream(path) << text;
  return path.string();
}

TEST(EngineController, FourChambersOnFourEnginesHoldTheirSharesAndTheSetPointAgainstALeakOnOne) {
  EngineLoop loop(gridWithoutReservoir());
  ASSERT_EQ(loop.geometry().chambers.size(), 4u);
  ASSERT_FALSE(loop.geometry().has_reservoir);
  const double f_set = loop.params().desired_downforce_n;
  // A crack-sized gap under the outer strips of chamber 1 (rear right): its engine works harder.
  const auto names = thermo::segmentNames(loop.geometry());
  std::vector<std::size_t> outer_1;
  for (std::size_t s = 0; s < loop.geometry().segments.size(); ++s) {
    if (loop.geometry().segments[s].volume_a == 0 && loop.geometry().segments[s].volume_b == kAmbient) outer_1.push_back(s);
  }
  ASSERT_FALSE(outer_1.empty());
  for (std::size_t s : outer_1) loop.leakAreas()[s] *= 2.0;
  const EngineTrace balanced = loop.run(15.0);
  loop.params().balance = false;
  const EngineTrace unbalanced = loop.run(15.0);
  std::printf("bench: engine-law: grid without reservoir, leak x2 on chamber 1: |P_F| %.2f mm balanced, %.2f mm "
              "without; speeds %.3f %.3f %.3f %.3f\n",
              1e3 * balanced.pf_norm_m.back(), 1e3 * unbalanced.pf_norm_m.back(), balanced.final_speed[0],
              balanced.final_speed[1], balanced.final_speed[2], balanced.final_speed[3]);
  EXPECT_NEAR(balanced.downforce_n.back(), f_set, 2e-3 * f_set);
  EXPECT_NEAR(unbalanced.downforce_n.back(), f_set, 2e-3 * f_set);
  // The leaky chamber's engine runs fastest; without balance the chambers hold equal suctions
  // (P_F at the area centre); with it P_F stays at the centre too, now by trims.
  for (int e = 1; e < 4; ++e) EXPECT_GT(balanced.final_speed[0], balanced.final_speed[e]) << e;
  EXPECT_LT(balanced.pf_norm_m.back(), 1e-3);
}

TEST(EngineController, ATiltedShareIsRebalancedByTheTrims) {
  // Without trims P_F sits where the chambers' equal suctions put it: at the centre of area.
  // Shift every chamber's target by hand (P_F off the centre) and the balance loop brings it back.
  EngineLoop loop(gridWithoutReservoir());
  const double f_set = loop.params().desired_downforce_n;
  const EngineController controller(loop.params());
  EngineControllerState state = controller.initialState();
  AdhesionMeasurement m;
  m.pressure_pa.assign(4, loop.robot().gas.ambient_pressure_pa - 2000.0);
  m.downforce_n = f_set;
  m.p_RobotPF_m = {0.05, 0.0};  // towards the front chambers 2 and 4
  for (int k = 0; k < 100; ++k) controller.step(state, m, k * kPeriodNs, kPeriodNs);
  // Front chambers (x > 0) pull less, rear ones more; the shares still give F*.
  EXPECT_GT(state.trim[1], 0.0);
  EXPECT_LT(state.trim[0], 0.0);
  EXPECT_LT(state.target_pa[1], state.target_pa[0]);
  double f = 0.0;
  for (int i = 0; i < 4; ++i) f += loop.geometry().chambers[i].area_m2 * state.target_pa[i];
  EXPECT_NEAR(f, f_set, 1e-9 * f_set);
}

// --- parameters, inputs, and the command model -------------------------------------------

TEST(EngineController, RejectsBadParametersAndMeasurements) {
  EngineLoop loop(shippedRobot("single-chamber"));
  auto p = loop.params();
  p.engine_chamber = {1};  // chamber 2 of a robot with one
  EXPECT_THROW(EngineController{p}, ConfigError);
  p = loop.params();
  p.engine_integral_s = 0.0;
  EXPECT_THROW(EngineController{p}, ConfigError);
  p = loop.params();
  p.engine_chamber.clear();
  EXPECT_THROW(EngineController{p}, ConfigError);
  const EngineController controller(loop.params());
  auto state = controller.initialState();
  AdhesionMeasurement m;
  m.pressure_pa = {100000.0, 100000.0};  // a reservoir's pressure too: not this robot
  EXPECT_THROW(controller.step(state, m, 0, kPeriodNs), std::invalid_argument);
  m.pressure_pa = {NAN};
  EXPECT_THROW(controller.step(state, m, 0, kPeriodNs), std::invalid_argument);
  // A robot with a reservoir has valves for this.
  const auto cromsci = loadRobotDescription(shippedRobot("cromsci"));
  EXPECT_THROW(engineControllerParamsFromRobot(cromsci, computeGeometry(cromsci)), ConfigError);
}

ControllerParams singleChamberParams(const std::vector<std::string>& overrides) {
  const Scenario s = loadScenario(std::string(CLIMBSIM_SCENARIOS_DIR) + "/hold-single-chamber.yaml", overrides);
  const RobotDescription robot = loadRobotDescription(s.robotPath());
  return controllerParams(s, robot, computeGeometry(robot));
}

TEST(EngineController, TheReferenceTypeWithoutAReservoirCommandsTheEnginesSpeedAndStatesItsSetPoint) {
  const ControllerModel model(singleChamberParams({}));
  ControllerState state = model.initialState();
  ASSERT_TRUE(state.engine_reference.has_value());
  EXPECT_FALSE(state.reference.has_value());
  ControllerInputs in;
  in.pressure_pa.emplace(1, 100000.0);
  in.downforce_n = 0.0;
  const ControllerOutputs out = model.step(state, in, 0, kPeriodNs);
  EXPECT_TRUE(out.valve_opening.empty());  // no valves: the command carries the set-point only
  EXPECT_EQ(out.downforce_setpoint_n, 700.0);
  ASSERT_EQ(out.engine_speed.size(), 1u);
  EXPECT_GT(out.engine_speed[0], 0.0);
  EXPECT_TRUE(out.commands_engines);

  // none: full speed; external: the client has the engines (and the set-point's valve command).
  ControllerState none_state = ControllerModel(singleChamberParams({"controller={type: none}"})).initialState();
  EXPECT_EQ(ControllerModel(singleChamberParams({"controller={type: none}"})).step(none_state, in, 0, kPeriodNs).engine_speed,
            std::vector<double>{1.0});
  const ControllerModel external(singleChamberParams({"controller={type: external}"}));
  EXPECT_FALSE(external.commandsValves());
  EXPECT_FALSE(external.commandsEngines());
  ControllerState external_state = external.initialState();
  EXPECT_TRUE(external.step(external_state, in, 0, kPeriodNs).engine_speed.empty());
  // The scenario's set-point replaces the robot file's.
  EXPECT_EQ(singleChamberParams({"controller={type: reference, downforce_n: 500}"}).engine_reference.desired_downforce_n,
            500.0);
}

}  // namespace
}  // namespace climbsim::controller
