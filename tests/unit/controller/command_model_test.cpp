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

}  // namespace
}  // namespace climbsim::controller
