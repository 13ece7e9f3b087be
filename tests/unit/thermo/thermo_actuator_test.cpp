/// Valves (pure delay, rate limit), engine lag, and what the model refuses.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "climbsim/errors.hpp"
#include "thermo_cromsci_params.hpp"
#include "thermo_model.hpp"

namespace climbsim::thermo {
namespace {

using testing::defaultCromsciParams;
using testing::idleInputs;

constexpr std::int64_t kMs = 1'000'000;

// Delay 20 ms, then 5 /s: the opening is exactly 0 up to 20 ms and exactly
// 0.005 per ms after, reaching 1 at 220 ms; a later command 0.4 at 300 ms starts at
// 320 ms and lands at 440 ms.
TEST(ThermoValve, DelayThenRateLimitExactTiming) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  ThermoInputs in = idleInputs(model.params());
  for (int ms = 0; ms < 500; ++ms) {
    in.valve_command[2] = ms < 300 ? 1.0 : 0.4;
    const ThermoOutputs out = model.step(state, in, state.t_ns, kMs);
    const int t = ms + 1;  // outputs are at the end of the step
    double expected = 0.0;
    if (t <= 20) expected = 0.0;
    else if (t <= 220) expected = 0.005 * (t - 20);
    else if (t <= 320) expected = 1.0;
    else if (t <= 440) expected = 1.0 - 0.005 * (t - 320);
    else expected = 0.4;
    ASSERT_NEAR(out.valve_opening[2], expected, 1e-12) << "t = " << t << " ms";
    for (int c = 0; c < model.params().valveCount(); ++c) {
      if (c != 2) {
        ASSERT_EQ(out.valve_opening[c], 0.0);
      }
    }
  }
  EXPECT_EQ(state.valve_opening[2], 0.4);  // lands exactly on the target
}

// The model ends its integration pieces where a valve lands, so a landing inside an
// exchange step gives the same trajectory as steps that end exactly there: a command
// 0.46 at t = 0 activates at 20 ms and lands at 20 + 0.46 * 200 = 112 ms, inside the 5 ms
// step [110, 115] but on the 1 ms grid. Tight tolerances: both are the ODE's solution.
TEST(ThermoValve, LandingInsideAStepEqualsSteppingToIt) {
  ThermoParams p = defaultCromsciParams();
  p.step_control.abs_tol = 1e-6;
  const ThermoModel model(p);
  ThermoInputs in = testing::suctionInputs(p, 0.0);
  in.valve_command[0] = 0.46;
  in.valve_command[3] = 0.17;  // lands at 54 ms: inside [50, 55], on the 1 ms grid
  ThermoState coarse = model.initialState();
  ThermoState fine = model.initialState();
  ThermoOutputs out_coarse, out_fine;
  for (int k = 0; k < 30; ++k) out_coarse = model.step(coarse, in, coarse.t_ns, 5 * kMs);
  for (int k = 0; k < 150; ++k) out_fine = model.step(fine, in, fine.t_ns, kMs);
  EXPECT_EQ(out_coarse.valve_opening[0], 0.46);
  EXPECT_EQ(out_coarse.valve_opening[3], 0.17);
  for (int i = 0; i < p.volumeCount(); ++i) {
    EXPECT_NEAR(out_coarse.pressure_pa[i], out_fine.pressure_pa[i], 1e-4) << "volume " << i;
  }
  // The air-mass balance holds across the pieces as it does across the steps.
  const double balance_coarse = out_coarse.air_mass_kg - out_coarse.ambient_inflow_kg + out_coarse.engine_outflow_kg;
  const double balance_fine = out_fine.air_mass_kg - out_fine.ambient_inflow_kg + out_fine.engine_outflow_kg;
  EXPECT_NEAR(balance_coarse, balance_fine, 1e-12 * out_fine.air_mass_kg);
}

// A delay that is not a multiple of the step: the command of step 0 activates 7 ms into
// a 5 ms step grid, i.e. 2 ms into the second step.
TEST(ThermoValve, ActivationInsideAStep) {
  ThermoParams p = defaultCromsciParams();
  p.valve.command_delay_s = 0.007;
  const ThermoModel model(p);
  ThermoState state = model.initialState();
  ThermoInputs in = idleInputs(p);
  in.valve_command[0] = 1.0;
  ThermoOutputs out = model.step(state, in, 0, 5 * kMs);
  EXPECT_EQ(out.valve_opening[0], 0.0);
  out = model.step(state, in, 5 * kMs, 5 * kMs);
  EXPECT_NEAR(out.valve_opening[0], 3e-3 * 5.0, 1e-12);
  out = model.step(state, in, 10 * kMs, 5 * kMs);
  EXPECT_NEAR(out.valve_opening[0], 8e-3 * 5.0, 1e-12);
}

// A command reversal mid-stroke turns the valve at the same rate, never jumps.
TEST(ThermoValve, RateLimitHoldsOnReversal) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  ThermoInputs in = idleInputs(model.params());
  double previous = 0.0;
  for (int ms = 0; ms < 400; ++ms) {
    in.valve_command[5] = (ms / 60) % 2 == 0 ? 1.0 : 0.0;
    const ThermoOutputs out = model.step(state, in, state.t_ns, kMs);
    ASSERT_LE(std::abs(out.valve_opening[5] - previous), 5e-3 + 1e-12) << "t = " << ms + 1 << " ms";
    ASSERT_GE(out.valve_opening[5], 0.0);
    ASSERT_LE(out.valve_opening[5], 1.0);
    previous = out.valve_opening[5];
  }
}

TEST(ThermoEngine, SpeedFollowsFirstOrderLag) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  ThermoInputs in = idleInputs(model.params());
  in.engines[1] = {true, 0.8};
  for (int k = 1; k <= 200; ++k) {
    const ThermoOutputs out = model.step(state, in, state.t_ns, 5 * kMs);
    ASSERT_NEAR(out.engine_speed[1], 0.8 * (1.0 - std::exp(-k * 5e-3 / 0.5)), 1e-12);
    ASSERT_EQ(out.engine_speed[0], 0.0);
  }
  in.engines[1].on = false;  // off: the speed decays from where it was
  const double s0 = state.engine_speed[1];
  const ThermoOutputs out = model.step(state, in, state.t_ns, 100 * kMs);
  EXPECT_NEAR(out.engine_speed[1], s0 * std::exp(-0.1 / 0.5), 1e-12);
}

TEST(ThermoInputs, BadSamplesAreRejectedAndStateKept) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState();
  const ThermoInputs good = idleInputs(model.params());
  const double nan = std::numeric_limits<double>::quiet_NaN();

  std::vector<std::pair<ThermoInputs, std::string>> bad;
  ThermoInputs in = good;
  in.valve_command[3] = 1.5;
  bad.push_back({in, "valve_command[3] = 1.5"});
  in = good;
  in.valve_command[0] = nan;
  bad.push_back({in, "valve_command[0] = nan"});
  in = good;
  in.leak_area_m2[7] = -1e-6;
  bad.push_back({in, "leak_area_m2[7] = -1e-06"});
  in = good;
  in.leak_area_m2[2] = INFINITY;
  bad.push_back({in, "leak_area_m2[2] = inf"});
  in = good;
  in.leak_area_m2.pop_back();
  bad.push_back({in, "leak_area_m2 has 17 entries, the robot has 18 sealing segments"});
  in = good;
  in.engines[0].speed = -0.1;
  bad.push_back({in, "engines[0].speed = -0.1"});
  in = good;
  in.engines.pop_back();
  bad.push_back({in, "engines has 2 entries, the robot has 3 engines"});
  in = good;
  in.valve_command.pop_back();
  bad.push_back({in, "valve_command has 6 entries, the robot has 7 valves"});

  for (const auto& [sample, text] : bad) {
    EXPECT_NE(validateInputs(model.params(), sample).find(text), std::string::npos)
        << validateInputs(model.params(), sample);
    const ThermoState before = state;
    EXPECT_THROW(model.step(state, sample, state.t_ns, kMs), InvalidInputError) << text;
    EXPECT_EQ(state.t_ns, before.t_ns);
    EXPECT_EQ(state.pressure_pa, before.pressure_pa);
    EXPECT_TRUE(state.pending_valve_commands.empty());
  }
  EXPECT_EQ(validateInputs(model.params(), good), "");
  EXPECT_NO_THROW(model.step(state, good, state.t_ns, kMs));
}

TEST(ThermoInputs, TimeMustContinueTheState) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState state = model.initialState(10 * kMs);
  const ThermoInputs in = idleInputs(model.params());
  EXPECT_THROW(model.step(state, in, 0, kMs), std::logic_error);
  EXPECT_THROW(model.step(state, in, 10 * kMs, 0), std::logic_error);
  EXPECT_NO_THROW(model.step(state, in, 10 * kMs, kMs));
  EXPECT_EQ(state.t_ns, 11 * kMs);
}

void expectConfigError(const ThermoParams& p, const std::string& text) {
  try {
    p.validate();
    ADD_FAILURE() << "no error for " << text;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(ThermoParams, ValidationNamesParameterAndValue) {
  EXPECT_NO_THROW(defaultCromsciParams().validate());
  ThermoParams p = defaultCromsciParams();
  p.chamber_volume_m3[2] = -1.0;
  expectConfigError(p, "chamber_volume_m3[2] = -1");
  p = defaultCromsciParams();
  p.reservoir_volume_m3 = 0.0;
  expectConfigError(p, "reservoir_volume_m3 = 0");
  p = defaultCromsciParams();
  p.chamber_area_m2[6] = std::numeric_limits<double>::quiet_NaN();
  expectConfigError(p, "chamber_area_m2[6] = nan");
  p = defaultCromsciParams();
  p.valve.discharge_coefficient = 1.2;
  expectConfigError(p, "valve.discharge_coefficient = 1.2");
  p = defaultCromsciParams();
  p.engines[1].speed_lag_s = 0.0;
  expectConfigError(p, "engines[1].speed_lag_s = 0");
  p = defaultCromsciParams();
  p.segments[4] = {3, 3};
  expectConfigError(p, "segments[4].volume_b = 3");
  p = defaultCromsciParams();
  p.segments[0] = {0, 8};
  expectConfigError(p, "segments[0].volume_b = 8");
  p = defaultCromsciParams();
  p.chamber_area_m2.pop_back();
  expectConfigError(p, "chamber_area_m2.size = 6 (must be equal to the number of chambers, 7)");
  p = defaultCromsciParams();
  p.has_reservoir = false;  // the engines still name the reservoir
  expectConfigError(p, "engines[0].chamber = -1 (must be a chamber, 0..6)");
  p = defaultCromsciParams();
  p.faults.push_back(PlantFault{PlantFault::Kind::kValveStuck, 0, 8, 0.5, 0});
  expectConfigError(p, "faults[0].chamber = 8 (must be in 1..7)");
  p = defaultCromsciParams();
  p.gas.temperature_k = -5.0;
  expectConfigError(p, "gas.temperature_k = -5");
  p = defaultCromsciParams();
  p.step_control.abs_tol = 0.0;
  expectConfigError(p, "integrator.abs_tol = 0");
  EXPECT_THROW(ThermoModel{p}, ConfigError);
}

TEST(ThermoDeterminism, SameInputsGiveBitIdenticalStates) {
  const ThermoModel model(defaultCromsciParams());
  ThermoState a = model.initialState(), b = model.initialState();
  ThermoInputs in = testing::suctionInputs(model.params(), 0.0);
  for (int k = 0; k < 300; ++k) {
    for (int c = 0; c < model.params().valveCount(); ++c) in.valve_command[c] = (k / 20 + c) % 3 * 0.5;
    const ThermoOutputs oa = model.step(a, in, a.t_ns, 5 * kMs);
    const ThermoOutputs ob = model.step(b, in, b.t_ns, 5 * kMs);
    ASSERT_EQ(oa.pressure_pa, ob.pressure_pa);
    ASSERT_EQ(oa.downforce_n, ob.downforce_n);
  }
}

}  // namespace
}  // namespace climbsim::thermo
