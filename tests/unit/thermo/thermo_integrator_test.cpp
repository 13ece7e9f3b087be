/// The integrators: convergence order of each tableau on a problem with a known solution
/// (catches a wrong coefficient), and no chatter when two chambers equalise.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dormand_prince.hpp"
#include "rosenbrock.hpp"
#include "thermo_cromsci_params.hpp"
#include "thermo_model.hpp"

namespace climbsim::thermo {
namespace {

// y0' = l (y0 - sin t) + cos t   -> y0 = sin t + exp(l t)
// y1' = -y1^2                    -> y1 = 1 / (1 + t)
// y2' = t y2                     -> y2 = exp(t^2 / 2)
// Non-autonomous and nonlinear, so that the f_t terms and the stage couplings matter.
class KnownSolution final : public OdeSystem {
 public:
  static constexpr double kLambda = -2.0;
  KnownSolution() : OdeSystem(3, 3) {}
  void rhs(double t, const OdeVector& y, OdeVector& f) const override {
    f.setZero(3);
    f[0] = kLambda * (y[0] - std::sin(t)) + std::cos(t);
    f[1] = -y[1] * y[1];
    f[2] = t * y[2];
  }
  void jacobian(double t, const OdeVector& y, OdeVector& f, OdeMatrix& j, OdeVector& ft) const override {
    rhs(t, y, f);
    j.setZero(3, 3);
    j(0, 0) = kLambda;
    j(1, 1) = -2.0 * y[1];
    j(2, 2) = t;
    ft.setZero(3);
    ft[0] = -kLambda * std::cos(t) - std::sin(t);
    ft[2] = y[2];
  }
  static OdeVector exact(double t) {
    OdeVector y = OdeVector::Zero(3);
    y[0] = std::sin(t) + std::exp(kLambda * t);
    y[1] = 1.0 / (1.0 + t);
    y[2] = std::exp(0.5 * t * t);
    return y;
  }
};

enum class Method { kRodas3, kRos2, kDopri };

// Error at t = 1 with a fixed step h (tolerance so loose that every step is accepted);
// `w_zero` lets ROS2 take every step with W = 0 (Heun), `euler` also continue from the
// Euler predictor of every such step.
double fixedStepError(Method method, double h, bool w_zero = false, bool euler = false) {
  KnownSolution sys;
  StepControl control;
  control.abs_tol = 1e6;
  control.rel_tol = 0.0;
  control.error_components = 3;
  control.max_step_s = h;
  // The Gershgorin bound of this Jacobian is at most 2 on [0, 1]: h * 2 <= 0.2 < 2.
  control.explicit_below = w_zero ? 2.0 : 0.0;
  control.euler_below = euler ? 1.0 : 0.0;
  OdeVector y = KnownSolution::exact(0.0);
  double step = h;
  IntegratorStats stats;
  if (method == Method::kDopri) {
    integrateDormandPrince(sys, 1.0, y, step, control, stats);
  } else {
    integrateRosenbrock(sys, method == Method::kRos2 ? RosenbrockMethod::kRos2 : RosenbrockMethod::kRodas3, 1.0, y,
                        step, control, stats);
  }
  EXPECT_EQ(stats.rejected_steps, 0);
  EXPECT_EQ(stats.explicit_steps, w_zero ? stats.accepted_steps : 0);
  if (method != Method::kDopri) {
    EXPECT_EQ(stats.jacobian_evals, w_zero ? 0 : stats.accepted_steps);
  }
  return (y - KnownSolution::exact(1.0)).head<3>().cwiseAbs().maxCoeff();
}

double observedOrder(Method method, bool w_zero = false, bool euler = false) {
  const double e1 = fixedStepError(method, 0.1, w_zero, euler);
  const double e2 = fixedStepError(method, 0.05, w_zero, euler);
  return std::log2(e1 / e2);
}

TEST(ThermoIntegrator, Rodas3IsThirdOrder) { EXPECT_NEAR(observedOrder(Method::kRodas3), 3.0, 0.3); }
TEST(ThermoIntegrator, Ros2IsSecondOrder) { EXPECT_NEAR(observedOrder(Method::kRos2), 2.0, 0.3); }
// ROS2 is a W-method: order 2 for any W, so its explicit steps (W = 0, f_t = 0: Heun's
// method) keep the order; continuing from the Euler predictor gives it up (order 1),
// which is why the model does so only where that predictor's error is far inside the
// tolerance.
TEST(ThermoIntegrator, Ros2WithWZeroIsSecondOrder) { EXPECT_NEAR(observedOrder(Method::kRos2, true), 2.0, 0.3); }
TEST(ThermoIntegrator, Ros2EulerContinuationIsFirstOrder) {
  EXPECT_NEAR(observedOrder(Method::kRos2, true, true), 1.0, 0.3);
}
TEST(ThermoIntegrator, DormandPrinceIsFifthOrder) { EXPECT_NEAR(observedOrder(Method::kDopri), 5.0, 0.5); }

TEST(ThermoIntegrator, AdaptiveStepMeetsTolerance) {
  KnownSolution sys;
  StepControl control;
  control.abs_tol = 1e-8;
  control.rel_tol = 1e-8;
  control.error_components = 3;
  for (const RosenbrockMethod m : {RosenbrockMethod::kRodas3, RosenbrockMethod::kRos2}) {
    OdeVector y = KnownSolution::exact(0.0);
    double step = 1e-3;
    IntegratorStats stats;
    integrateRosenbrock(sys, m, 2.0, y, step, control, stats);
    EXPECT_LT((y - KnownSolution::exact(2.0)).head<3>().cwiseAbs().maxCoeff(), 1e-5);
  }
}

// Two chambers joined by a valve-sized opening, everything else shut, exchange periods
// far longer than the equalisation time constant (about 0.2 ms near equality): the
// pressures must approach each other monotonically and the flow may never change sign.
struct ChatterCase {
  IntegratorKind integrator;
  std::int64_t dt_ns;
};

class ThermoChatter : public ::testing::TestWithParam<ChatterCase> {};

TEST_P(ThermoChatter, TwoChambersEqualiseMonotonically) {
  ThermoParams p = testing::defaultCromsciParams();
  p.engines.clear();
  p.integrator = GetParam().integrator;
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  const double p_o = p.gas.ambient_pressure_pa;
  state.pressure_pa[0] = p_o - 5000.0;
  ThermoInputs in = testing::idleInputs(p);
  std::fill(in.leak_area_m2.begin(), in.leak_area_m2.end(), 0.0);
  const int wall = testing::kRadialWall0;  // chamber 1 <-> chamber 2
  in.leak_area_m2[wall] = 4.2e-4;
  const double p_eq = p_o - 5000.0 * p.chamber_volume_m3[0] / (p.chamber_volume_m3[0] + p.chamber_volume_m3[1]);

  double p1_prev = state.pressure_pa[0], p2_prev = state.pressure_pa[1];
  const std::int64_t end_ns = 300'000'000;
  while (state.t_ns < end_ns) {
    const ThermoOutputs out = model.step(state, in, state.t_ns, GetParam().dt_ns);
    const double p1 = out.pressure_pa[0], p2 = out.pressure_pa[1];
    ASSERT_GE(p1, p1_prev - 1e-9) << "t_ns " << out.t_ns;
    ASSERT_LE(p2, p2_prev + 1e-9) << "t_ns " << out.t_ns;
    ASSERT_LE(p1, p2 + 1e-9) << "overshoot at t_ns " << out.t_ns << ": " << p1 - p2;
    ASSERT_LE(out.segment_mass_flow_kgps[wall], 1e-15) << "flow reversed at t_ns " << out.t_ns;
    p1_prev = p1;
    p2_prev = p2;
  }
  EXPECT_NEAR(p1_prev, p_eq, 1e-6);
  EXPECT_NEAR(p2_prev, p_eq, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Integrators, ThermoChatter,
                         ::testing::Values(ChatterCase{IntegratorKind::kRos2, 5'000'000},
                                           ChatterCase{IntegratorKind::kRos2, 1'000'000},
                                           ChatterCase{IntegratorKind::kRos2, 100'000}));

// Why Ros2 and not Rodas3 is the default: Rodas3's R(z) is negative for z < -2.9, so
// with 5 ms steps over the 0.2 ms equalisation mode the pressures cross (by about 1e-7 Pa,
// far inside the tolerance, but a sign flip of the flow all the same).
TEST(ThermoChatterRodas3, OvershootsOnStiffMode) {
  ThermoParams p = testing::defaultCromsciParams();
  p.engines.clear();
  p.integrator = IntegratorKind::kRodas3;
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  state.pressure_pa[0] = p.gas.ambient_pressure_pa - 5000.0;
  ThermoInputs in = testing::idleInputs(p);
  std::fill(in.leak_area_m2.begin(), in.leak_area_m2.end(), 0.0);
  in.leak_area_m2[testing::kRadialWall0] = 4.2e-4;
  bool crossed = false;
  for (int k = 0; k < 60; ++k) {
    const ThermoOutputs out = model.step(state, in, state.t_ns, 5'000'000);
    crossed = crossed || out.pressure_pa[0] > out.pressure_pa[1];
  }
  EXPECT_TRUE(crossed);
}

// Every valve ramping and landing inside every 5 ms exchange period (the benchmark's worst
// case): the default ROS2 (explicit where the stiffness bound allows, Euler continuation
// where its error is tiny) and the all-implicit ROS2 both stay within 10 tolerances of a
// tight Rodas3 reference, and the default does it with fewer evaluations.
TEST(ThermoIntegrator, StiffnessSwitchKeepsAccuracyWithMovingValves) {
  struct Run {
    std::vector<std::vector<double>> pressures;
    IntegratorStats stats;
  };
  const auto run = [](const ThermoParams& p) {
    const ThermoModel model(p);
    ThermoState state = model.initialState();
    Run r;
    for (int k = 0; k < 400; ++k) {
      ThermoInputs in = testing::suctionInputs(p, 1.0);
      const double t = static_cast<double>(state.t_ns) * 1e-9;
      for (int c = 0; c < p.valveCount(); ++c) in.valve_command[c] = 0.5 + 0.45 * std::sin(2.0 * testing::kPi * 0.4 * t + c);
      const ThermoOutputs out = model.step(state, in, state.t_ns, 5'000'000);
      r.pressures.push_back(out.pressure_pa);
      r.stats.rhs_evals += out.integrator.rhs_evals + out.integrator.jacobian_evals;
      r.stats.explicit_steps += out.integrator.explicit_steps;
    }
    return r;
  };
  const auto maxError = [](const Run& a, const Run& ref) {
    double e = 0.0;
    for (std::size_t k = 0; k < ref.pressures.size(); ++k) {
      for (std::size_t i = 0; i < ref.pressures[k].size(); ++i) e = std::max(e, std::abs(a.pressures[k][i] - ref.pressures[k][i]));
    }
    return e;
  };
  ThermoParams ref_params = testing::defaultCromsciParams();
  ref_params.integrator = IntegratorKind::kRodas3;
  ref_params.step_control.abs_tol = 1e-7;
  const Run ref = run(ref_params);

  const ThermoParams switching_params = testing::defaultCromsciParams();
  ASSERT_GT(switching_params.step_control.explicit_below, 0.0);
  ThermoParams implicit_params = switching_params;
  implicit_params.step_control.explicit_below = 0.0;
  implicit_params.step_control.euler_below = 0.0;
  const Run switching = run(switching_params);
  const Run implicit = run(implicit_params);

  const double tol = switching_params.step_control.abs_tol;
  EXPECT_LE(maxError(switching, ref), 10.0 * tol);
  EXPECT_LE(maxError(implicit, ref), 10.0 * tol);
  EXPECT_GT(switching.stats.explicit_steps, 0);
  EXPECT_EQ(implicit.stats.explicit_steps, 0);
  EXPECT_LT(switching.stats.rhs_evals, implicit.stats.rhs_evals);
}

}  // namespace
}  // namespace climbsim::thermo
