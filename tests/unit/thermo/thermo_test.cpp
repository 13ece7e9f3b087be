/// Physical facts of the thermo model: mass balance, a closed
/// system's equilibrium, the analytic venting law, the engines' steady state against an
/// independent root-find, and where the downforce acts.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>

#include "steady_airflow.hpp"
#include "thermo_cromsci_params.hpp"
#include "thermo_model.hpp"

namespace climbsim::thermo {
namespace {

using testing::basicLeakAreas;
using testing::defaultCromsciParams;
using testing::idleInputs;
using testing::kOuterArc0;
using testing::run;
using testing::suctionInputs;

constexpr std::int64_t kStepNs = 5'000'000;

// --- mass balance ------------------------------------------------------------------

// The ODE dp_i/dt = -(kappa R T / V_i) sum mdot conserves sum p_i V_i / (kappa R T) plus
// what crossed the boundary; the model reports that sum as air_mass_kg.
TEST(ThermoPhysics, MassBalanceEnginesValvesAndLeaks) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  ThermoInputs in = suctionInputs(model.params(), 0.0);
  in.leak_area_m2[kOuterArc0] *= 10.0;
  const double mass0 = run(model, state, idleInputs(model.params()), 1).air_mass_kg;
  const double in0 = state.ambient_inflow_kg, out0 = state.engine_outflow_kg;

  ThermoOutputs out;
  for (int k = 0; k < 600; ++k) {
    // Valves wander so that the rate limit, the delay and the cuts are all exercised.
    for (int c = 0; c < model.params().valveCount(); ++c) in.valve_command[c] = 0.5 + 0.5 * std::sin(0.05 * k + c);
    out = model.step(state, in, state.t_ns, kStepNs);
  }
  const double stored = out.air_mass_kg - mass0;
  const double crossed = (out.ambient_inflow_kg - in0) - (out.engine_outflow_kg - out0);
  ASSERT_GT(std::abs(stored), 1e-4);            // the reservoir really was evacuated
  ASSERT_GT(out.engine_outflow_kg - out0, 0.1);  // and a lot of air went through
  EXPECT_LE(std::abs(stored - crossed), 1e-9 * std::abs(stored)) << "stored " << stored << " crossed " << crossed;
}

// With kappa = 1 the conserved quantity is the ideal-gas mass sum p_i V_i / (R T) itself,
// computed here from the pressures, not from the model's own air_mass_kg.
TEST(ThermoPhysics, MassBalanceIdealGasMassWithKappaOne) {
  ThermoParams p = defaultCromsciParams();
  p.gas.kappa = 1.0;
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  auto ideal_mass = [&](const ThermoState& s) {
    double m = s.pressure_pa[p.reservoir()] * p.reservoir_volume_m3;
    for (int i = 0; i < p.chamberCount(); ++i) m += s.pressure_pa[i] * p.chamber_volume_m3[i];
    return m / (p.gas.gas_constant_jpkgk * p.gas.temperature_k);
  };
  const double mass0 = ideal_mass(state);
  ThermoInputs in = suctionInputs(p, 0.7);
  in.leak_area_m2[3] *= 4.0;
  run(model, state, in, 400);
  const double stored = ideal_mass(state) - mass0;
  const double crossed = state.ambient_inflow_kg - state.engine_outflow_kg;
  ASSERT_GT(std::abs(stored), 1e-4);
  EXPECT_LE(std::abs(stored - crossed), 1e-9 * std::abs(stored));
}

// --- closed system -----------------------------------------------------------------

TEST(ThermoPhysics, ClosedSystemSettlesAtMassWeightedPressure) {
  ThermoParams p = defaultCromsciParams();
  p.engines.clear();
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  double pv = 0.0, v = 0.0;
  for (int i = 0; i < p.volumeCount(); ++i) {
    state.pressure_pa[i] = 100000.0 - 1500.0 * (i + 1);
    const double vol = i < p.chamberCount() ? p.chamber_volume_m3[i] : p.reservoir_volume_m3;
    pv += state.pressure_pa[i] * vol;
    v += vol;
  }
  const double p_eq = pv / v;
  ThermoInputs in = idleInputs(p);
  for (int s = 0; s < 6; ++s) in.leak_area_m2[kOuterArc0 + s] = 0.0;  // no way to the ambient
  std::fill(in.valve_command.begin(), in.valve_command.end(), 1.0);
  const ThermoOutputs out = run(model, state, in, 600);  // 3 s
  for (int i = 0; i < p.volumeCount(); ++i) EXPECT_NEAR(out.pressure_pa[i], p_eq, 1e-3) << "volume " << i;
  EXPECT_EQ(out.ambient_inflow_kg, 0.0);
  EXPECT_EQ(out.engine_outflow_kg, 0.0);
}

// --- venting: analytic solution ----------------------------------------------------

// One chamber, one orifice of area A to the ambient, u = |p - p_o| above the laminar
// threshold: du/dt = -(kappa R T / V) A sqrt(2 rho u), so
//   sqrt(u(t)) = sqrt(u0) - c t / 2,  c = kappa R T A sqrt(2 rho) / V.
class ThermoVenting : public ::testing::TestWithParam<double> {};

TEST_P(ThermoVenting, FollowsAnalyticSquareRootLaw) {
  ThermoParams p = defaultCromsciParams();
  p.step_control.abs_tol = 1e-6;
  p.step_control.rel_tol = 1e-12;
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  const double u0 = std::abs(GetParam());
  state.pressure_pa[0] = p.gas.ambient_pressure_pa + GetParam();
  ThermoInputs in = idleInputs(p);
  std::fill(in.leak_area_m2.begin(), in.leak_area_m2.end(), 0.0);
  const double area = 1e-5;
  in.leak_area_m2[kOuterArc0] = area;
  const GasParams& g = p.gas;
  const double c = g.kappa * g.gas_constant_jpkgk * g.temperature_k * area *
                   std::sqrt(2.0 * g.orifice_density_kgpm3) / p.chamber_volume_m3[0];
  int checked = 0;
  double worst = 0.0;
  for (int k = 1;; ++k) {
    const ThermoOutputs out = model.step(state, in, state.t_ns, kStepNs);
    const double t = k * 5e-3;
    const double root = std::sqrt(u0) - 0.5 * c * t;
    const double u_exact = root * root;
    if (root <= 0.0 || u_exact < 2.0 * p.laminar_threshold_pa) break;
    const double u = std::abs(out.pressure_pa[0] - g.ambient_pressure_pa);
    worst = std::max(worst, std::abs(u - u_exact));
    EXPECT_NEAR(u, u_exact, 1e-7 * u_exact + 1e-3) << "t = " << t;
    ++checked;
  }
  EXPECT_GT(checked, 30);
  RecordProperty("worst_abs_error_pa", std::to_string(worst));
}

INSTANTIATE_TEST_SUITE_P(SuctionAndOverpressure, ThermoVenting, ::testing::Values(-20000.0, 15000.0));

// --- steady state against an independent root-find ----------------------------------

// The oracle: tests/support/steady_airflow.hpp (orifice law typed in again, damped Newton).

TEST(ThermoPhysics, SteadyStateMatchesIndependentRootFind) {
  const ThermoParams p = defaultCromsciParams();
  const ThermoModel model(p);
  for (const double opening : {0.3, 1.0}) {
    ThermoState state = model.initialState();
    ThermoInputs in = suctionInputs(p, opening);
    in.leak_area_m2[kOuterArc0] *= 6.0;        // one chamber leaks more: no symmetry to hide behind
    in.leak_area_m2[kOuterArc0 + 3] *= 2.5;
    const ThermoOutputs out = run(model, state, in, 6000);  // 30 s
    bool converged = false;
    const auto expected = testing::steadyPressures(p, in.leak_area_m2, testing::uniformOpenings(opening), &converged);
    ASSERT_TRUE(converged) << "root-find did not converge";
    for (int i = 0; i < p.volumeCount(); ++i) {
      const double suction_model = p.gas.ambient_pressure_pa - out.pressure_pa[i];
      const double suction_root = p.gas.ambient_pressure_pa - expected[i];
      ASSERT_GT(suction_root, 100.0);
      EXPECT_NEAR(suction_model, suction_root, 1e-3 * suction_root) << "volume " << i << " opening " << opening;
    }
  }
}

// --- downforce and its point of action ------------------------------------------------

ThermoOutputs steadyState(const ThermoModel& model, const ThermoInputs& in) {
  ThermoState state = model.initialState();
  return run(model, state, in, 3000);  // 15 s
}

TEST(ThermoDownforce, SymmetricLeaksPutPointOfActionAtCentre) {
  const ThermoModel model(defaultCromsciParams());
  const ThermoOutputs out = steadyState(model, suctionInputs(model.params(), 0.5));
  EXPECT_GT(out.downforce_n, 1000.0);
  EXPECT_NEAR(out.p_RobotPF_m[0], 0.0, 1e-9);
  EXPECT_NEAR(out.p_RobotPF_m[1], 0.0, 1e-9);
}

TEST(ThermoDownforce, LeakingChamberMovesPointOfActionAway) {
  const ThermoModel model(defaultCromsciParams());
  ThermoInputs in = suctionInputs(model.params(), 0.5);
  in.leak_area_m2[kOuterArc0] *= 20.0;  // chamber 1, centred on +x
  const ThermoOutputs out = steadyState(model, in);
  EXPECT_LT(out.p_RobotPF_m[0], -1e-3);           // towards -x, away from chamber 1
  EXPECT_NEAR(out.p_RobotPF_m[1], 0.0, 1e-9);     // chambers 2/6 and 3/5 mirror each other
  EXPECT_GT(out.pressure_pa[0], out.pressure_pa[3]);
}

TEST(ThermoDownforce, ForceFallsMonotonicallyAsOneLeakGrows) {
  const ThermoModel model(defaultCromsciParams());
  double previous = INFINITY;
  for (const double factor : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 300.0}) {
    ThermoInputs in = suctionInputs(model.params(), 0.5);
    in.leak_area_m2[kOuterArc0 + 2] *= factor;
    const double force = steadyState(model, in).downforce_n;
    EXPECT_LT(force, previous) << "leak factor " << factor;
    previous = force;
  }
}

TEST(ThermoDownforce, NoPullPutsPointOfActionAtAreaCentroid) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  std::fill(state.pressure_pa.begin(), state.pressure_pa.end(), model.params().gas.ambient_pressure_pa);
  state.pressure_pa[0] += 3000.0;  // chamber 1 pushes, nothing pulls
  ThermoInputs in = idleInputs(model.params());
  std::fill(in.leak_area_m2.begin(), in.leak_area_m2.end(), 0.0);
  const ThermoOutputs out = model.step(state, in, 0, kStepNs);
  EXPECT_LT(out.downforce_n, 0.0);
  EXPECT_NEAR(out.p_RobotPF_m[0], 0.0, 1e-12);  // the symmetric robot's area centroid
  EXPECT_NEAR(out.p_RobotPF_m[1], 0.0, 1e-12);
  EXPECT_GT(out.suction_moment_nm[0] * out.downforce_n, 0.0);  // moment keeps the side
}

}  // namespace
}  // namespace climbsim::thermo
