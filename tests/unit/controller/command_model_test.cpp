// The controller's command model on the contract: everything that evolves is in the State, so
// one model steps several states in any interleaving and each gives what it gives alone.

#include <gtest/gtest.h>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "command_model.hpp"

namespace climbsim::controller {
namespace {

constexpr std::int64_t kDt = 5'000'000;

ControllerParams paramsOf(const std::vector<std::string>& overrides) {
  const Scenario s = loadScenario(std::string(CLIMBSIM_SCENARIOS_DIR) + "/crack-descent.yaml", overrides);
  const RobotDescription robot = loadRobotDescription(s.robotPath());
  return controllerParams(s, robot, computeGeometry(robot));
}

/// Thermo values of step k of a made-up run whose suction builds at a rate `rate_pa` per step.
ControllerInputs inputsAt(int k, double rate_pa) {
  ControllerInputs in;
  in.pressure_pa.emplace(8, 101325.0 - rate_pa * k);  // the default robot: 7 chambers and the reservoir
  in.downforce_n = 10.0 * rate_pa * k;
  in.p_RobotPF_m = {1e-4 * k, -2e-4 * k};
  return in;
}

TEST(ControllerModel, TwoStatesSteppedInterleavedGiveWhatEachGivesAlone) {
  const ControllerModel model(paramsOf({}));
  const auto run = [&](ControllerState& state, int k, double rate) {
    return model.step(state, inputsAt(k, rate), k * kDt, kDt).valve_opening;
  };
  std::vector<std::vector<double>> interleaved_a, interleaved_b, alone_a, alone_b;
  ControllerState a = model.initialState(), b = model.initialState();
  for (int k = 0; k < 400; ++k) {  // two runs whose suction builds at different rates, in turn
    interleaved_a.push_back(run(a, k, 20.0));
    interleaved_b.push_back(run(b, k, 55.0));
  }
  ControllerState a2 = model.initialState(), b2 = model.initialState();
  for (int k = 0; k < 400; ++k) alone_a.push_back(run(a2, k, 20.0));
  for (int k = 0; k < 400; ++k) alone_b.push_back(run(b2, k, 55.0));
  EXPECT_EQ(interleaved_a, alone_a);
  EXPECT_EQ(interleaved_b, alone_b);
  EXPECT_NE(alone_a, alone_b);  // the two runs differ: the test would see a state mixed up
  EXPECT_EQ(a.reference->force_demand_n, a2.reference->force_demand_n);
}

TEST(ControllerModel, TheHeldMeasurementKeepsTheLastValidValues) {
  const ControllerModel model(paramsOf({"controller={type: none}"}));
  ControllerState state = model.initialState();
  EXPECT_EQ(state.measured.pressure_pa[0], paramsOf({}).reference.ambient_pressure_pa);
  model.step(state, inputsAt(10, 100.0), 0, kDt);
  const ControllerOutputs out = model.step(state, ControllerInputs{}, kDt, kDt);  // nothing new: held
  EXPECT_EQ(state.measured.pressure_pa[0], 101325.0 - 1000.0);
  EXPECT_EQ(state.measured.downforce_n, 10000.0);
  EXPECT_EQ(out.valve_opening, std::vector<double>(7, 0.0));  // none: closed, one per chamber
  EXPECT_EQ(out.downforce_setpoint_n, 0.0);                             // none: no set-point
  EXPECT_TRUE(out.commands_valves);
}

TEST(ControllerModel, ARecordedControllerHoldsEachRecordedCommandFromItsStepUntilTheNext) {
  // The recorded commands of steps 2 and 5 (ValveCommand) and 3 (EngineCommand): before the
  // first the valves are closed and the engines at full speed, then each holds until the next,
  // whatever the measurement says; the set-point is the recorded controller's.
  ControllerParams params = paramsOf({"controller={type: none}"});
  params.kind = Scenario::ControllerKind::kRecorded;
  params.recorded.valves = {{2 * kDt, std::vector<double>(7, 0.25), 2100.0},
                            {5 * kDt, {1.0, 0.0, 0.5, 0.5, 0.5, 0.5, 0.125}, 1900.0}};
  params.recorded.engines = {{3 * kDt, std::vector<double>(static_cast<std::size_t>(params.engine_count), 0.5)}};
  const ControllerModel model(params);
  ControllerState state = model.initialState();
  std::vector<ControllerOutputs> out;
  for (int k = 0; k < 8; ++k) out.push_back(model.step(state, inputsAt(k, 40.0 * k), k * kDt, kDt));
  const std::vector<double> full(static_cast<std::size_t>(params.engine_count), 1.0);
  for (int k : {0, 1}) {
    EXPECT_EQ(out[k].valve_opening, std::vector<double>(7, 0.0)) << k;
    EXPECT_EQ(out[k].downforce_setpoint_n, 0.0) << k;
    EXPECT_EQ(out[k].engine_speed, full) << k;
  }
  for (int k : {2, 3, 4}) {
    EXPECT_EQ(out[k].valve_opening, params.recorded.valves[0].opening) << k;
    EXPECT_EQ(out[k].downforce_setpoint_n, 2100.0) << k;
  }
  for (int k : {5, 6, 7}) {
    EXPECT_EQ(out[k].valve_opening, params.recorded.valves[1].opening) << k;
    EXPECT_EQ(out[k].downforce_setpoint_n, 1900.0) << k;
  }
  EXPECT_EQ(out[2].engine_speed, full);
  for (int k = 3; k < 8; ++k) EXPECT_EQ(out[k].engine_speed, params.recorded.engines[0].speed) << k;
  EXPECT_TRUE(out[0].commands_valves);
  EXPECT_TRUE(out[0].commands_engines);
  // Between steps (a run of another step length) the command of the last recorded step before holds.
  EXPECT_EQ(model.step(state, {}, 5 * kDt - 1, kDt).valve_opening, params.recorded.valves[0].opening);
}

}  // namespace
}  // namespace climbsim::controller
