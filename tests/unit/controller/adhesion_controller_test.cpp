// The reference adhesion controller in a closed loop with the real thermo model (no DDS):
// the loop as the lockstep runs it, the controller seeing the plant's outputs of the previous
// exchange period.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "adhesion_controller.hpp"
#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "thermo_model.hpp"

namespace climbsim::controller {
namespace {

constexpr std::int64_t kPeriodNs = 5'000'000;  // 5 ms exchange period
constexpr double kPeriodS = 5e-3;

struct LoopTrace {
  std::vector<double> t_s;
  std::vector<double> downforce_n;
  std::vector<double> pf_norm_m;
  double min_opening = 1.0;
  double max_opening = 0.0;
};

class ClosedLoop {
 public:
  ClosedLoop() {
    robot_ = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
    geometry_ = computeGeometry(robot_);
    thermo_params_ = thermo::thermoParamsFromRobot(robot_, geometry_);
    controller_params_ = adhesionControllerParamsFromRobot(robot_, geometry_);
    leak_area_m2_ = thermo::basicLeakAreas(robot_, geometry_);
  }

  /// Multiplies the leak area of the named segment (a crack under it).
  void scaleLeak(const std::string& segment, double factor) {
    const auto names = thermo::segmentNames(geometry_);
    const auto it = std::find(names.begin(), names.end(), segment);
    ASSERT_NE(it, names.end());
    leak_area_m2_[it - names.begin()] *= factor;
  }

  AdhesionControllerParams& controllerParams() { return controller_params_; }

  /// Runs the loop for duration_s; set_point_at(t) may change F* on the way.
  LoopTrace run(double duration_s, const std::function<double(double)>& set_point_at = {}) {
    thermo::ThermoModel model(thermo_params_);
    AdhesionController controller(controller_params_);
    auto state = model.initialState(0);
    thermo::ThermoInputs inputs;
    inputs.leak_area_m2 = leak_area_m2_;
    inputs.engines.assign(thermo_params_.engines.size(), thermo::EngineCommand{true, 1.0});
    AdhesionMeasurement measured;
    measured.pressure_pa.fill(robot_.gas.ambient_pressure_pa);
    LoopTrace trace;
    const long steps = std::lround(duration_s / kPeriodS);
    for (long k = 0; k < steps; ++k) {
      const double t_s = k * kPeriodS;
      if (set_point_at) controller.setDesiredDownforce(set_point_at(t_s));
      const auto openings = controller.step(measured, kPeriodS);
      for (int i = 0; i < kValveCount; ++i) {
        inputs.valve_command[i] = openings[i];
        trace.min_opening = std::min(trace.min_opening, openings[i]);
        trace.max_opening = std::max(trace.max_opening, openings[i]);
      }
      const auto out = model.step(state, inputs, k * kPeriodNs, kPeriodNs);
      std::copy(out.pressure_pa.begin(), out.pressure_pa.end(), measured.pressure_pa.begin());
      measured.downforce_n = out.downforce_n;
      measured.p_RobotPF_m = out.p_RobotPF_m;
      trace.t_s.push_back(t_s + kPeriodS);
      trace.downforce_n.push_back(out.downforce_n);
      trace.pf_norm_m.push_back(std::hypot(out.p_RobotPF_m[0], out.p_RobotPF_m[1]));
    }
    return trace;
  }

  const RobotDescription& robot() const { return robot_; }

 private:
  RobotDescription robot_;
  RobotGeometry geometry_;
  thermo::ThermoParams thermo_params_;
  AdhesionControllerParams controller_params_;
  std::vector<double> leak_area_m2_;
};

/// Largest |x - ref| / ref over the samples with t in [from_s, to_s].
double maxRelativeDeviation(const LoopTrace& tr, double ref, double from_s, double to_s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    if (tr.t_s[i] >= from_s && tr.t_s[i] <= to_s) worst = std::max(worst, std::abs(tr.downforce_n[i] - ref) / ref);
  }
  return worst;
}

double maxOver(const std::vector<double>& v, const LoopTrace& tr, double from_s, double to_s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < tr.t_s.size(); ++i) {
    if (tr.t_s[i] >= from_s && tr.t_s[i] <= to_s) worst = std::max(worst, v[i]);
  }
  return worst;
}

TEST(AdhesionController, HoldsTheSetPointOnAFlatWall) {
  ClosedLoop loop;
  const double f_set = loop.robot().adhesion.desired_downforce_n;
  const auto tr = loop.run(8.0);
  // Settled after the engines have spun up (lag 0.5 s) and the valve loops have converged.
  EXPECT_LT(maxRelativeDeviation(tr, f_set, 5.0, 8.0), 0.01);
  EXPECT_GE(tr.min_opening, 0.0);
  EXPECT_LE(tr.max_opening, 1.0);
  // A symmetric robot on a flat wall: P_F stays at the centre (a few mm at most).
  EXPECT_LT(maxOver(tr.pf_norm_m, tr, 5.0, 8.0), 0.005);
}

TEST(AdhesionController, CompensatesALeakingChamberAndRecentresPF) {
  ClosedLoop balanced;
  balanced.scaleLeak("outer2", 25.0);
  balanced.scaleLeak("radial2_3", 25.0);
  // A crack under chamber 2: its valve saturates and the chamber falls short of its target.
  const double f_set = 1800.0;
  const auto set_point = [&](double) { return f_set; };
  const auto with_balance = balanced.run(10.0, set_point);
  EXPECT_LT(maxRelativeDeviation(with_balance, f_set, 7.0, 10.0), 0.01);

  ClosedLoop unbalanced;
  unbalanced.scaleLeak("outer2", 25.0);
  unbalanced.scaleLeak("radial2_3", 25.0);
  unbalanced.controllerParams().balance = false;
  const auto without_balance = unbalanced.run(10.0, set_point);
  const double pf_balanced = with_balance.pf_norm_m.back();
  const double pf_unbalanced = without_balance.pf_norm_m.back();
  // Without the balance loop the leaking chamber falls short of its target and P_F moves away
  // from it; with it the opposite chambers pull less and P_F comes back towards the centre.
  EXPECT_GT(pf_unbalanced, 0.01);
  EXPECT_LT(pf_balanced, 0.25 * pf_unbalanced);
  EXPECT_LT(maxRelativeDeviation(without_balance, f_set, 7.0, 10.0), 0.01);
}

TEST(AdhesionController, RecoversFromAnUnreachableSetPointWithoutWindup) {
  ClosedLoop loop;
  const double f_set = loop.robot().adhesion.desired_downforce_n;
  // The engines cannot give more than dp_max over the whole area: 12 kN is out of reach for
  // 4 s; the loops saturate. Then back to the normal set-point.
  const auto tr = loop.run(12.0, [&](double t_s) { return t_s < 4.0 ? 12000.0 : f_set; });
  EXPECT_LT(maxRelativeDeviation(tr, f_set, 9.0, 12.0), 0.01);
  for (double f : tr.downforce_n) EXPECT_TRUE(std::isfinite(f));
}

TEST(AdhesionController, ForceFallsWhenTheSetPointFalls) {
  ClosedLoop low;
  const auto tr_low = low.run(8.0, [](double) { return 1500.0; });
  ClosedLoop high;
  const auto tr_high = high.run(8.0, [](double) { return 2500.0; });
  EXPECT_LT(maxRelativeDeviation(tr_low, 1500.0, 5.0, 8.0), 0.01);
  EXPECT_LT(maxRelativeDeviation(tr_high, 2500.0, 5.0, 8.0), 0.01);
}

TEST(AdhesionController, RejectsBadParametersAndMeasurements) {
  AdhesionControllerParams p;
  p.chamber_area_m2.fill(0.05);
  EXPECT_NO_THROW(AdhesionController{p});
  auto bad = p;
  bad.desired_downforce_n = -1.0;
  EXPECT_THROW(AdhesionController{bad}, ConfigError);
  bad = p;
  bad.chamber_area_m2[3] = 0.0;
  EXPECT_THROW(AdhesionController{bad}, ConfigError);
  bad = p;
  bad.max_trim = 1.0;
  EXPECT_THROW(AdhesionController{bad}, ConfigError);

  AdhesionController c(p);
  AdhesionMeasurement m;
  m.pressure_pa.fill(100000.0);
  const auto before = c.step(m, 0.005);
  m.downforce_n = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(c.step(m, 0.005), std::invalid_argument);
  EXPECT_EQ(c.openings(), before);
  m.downforce_n = 0.0;
  EXPECT_THROW(c.step(m, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::controller
