// The controller node without DDS: commands per controller type, the drive schedule by step
// time, bad thermo samples dropped and the last valid measurement held.

#include <gtest/gtest.h>

#include <limits>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "controller_node.hpp"

namespace climbsim::controller {
namespace {

Scenario scenarioWith(const std::vector<std::string>& overrides) {
  return loadScenario(std::string(CLIMBSIM_SCENARIOS_DIR) + "/crack-descent.yaml", overrides);
}

ControllerNode nodeFor(const Scenario& s) {
  const RobotDescription robot = loadRobotDescription(s.robotPath());
  return ControllerNode(controllerParams(s, robot, computeGeometry(robot)));
}

climbsim::ChamberState stateAt(double pressure_pa) {
  climbsim::ChamberState s;
  s.source("thermo");
  s.pressure_pa().assign(8, pressure_pa);
  return s;
}

climbsim::AdhesionForce forceOf(double f_n) {
  climbsim::AdhesionForce f;
  f.source("thermo");
  f.downforce_n(f_n);
  return f;
}

constexpr std::int64_t kDt = 5'000'000;

TEST(ControllerNode, DriveScheduleFollowsStepTime) {
  auto node = nodeFor(scenarioWith({}));
  // crack-descent: at rest until t = 2 s, then 5 cm/s along R's x.
  EXPECT_EQ(node.step(1'995'000'000, kDt, {}, {}).drive.vx_mps(), 0.0);
  EXPECT_EQ(node.step(2'000'000'000, kDt, {}, {}).drive.vx_mps(), 0.05);
}

TEST(ControllerNode, FixedNoneAndExternalTypes) {
  auto fixed = nodeFor(scenarioWith({"controller={type: fixed, valves: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]}"}));
  const auto c = fixed.step(0, kDt, {}, {});
  ASSERT_TRUE(c.valves.has_value());
  EXPECT_EQ(c.valves->opening()[6], 0.7);
  ASSERT_TRUE(c.engines.has_value());
  ASSERT_EQ(c.engines->engines().size(), 3u);
  EXPECT_TRUE(c.engines->engines()[0].on());

  auto none = nodeFor(scenarioWith({"controller={type: none}"}));
  const auto n = none.step(0, kDt, {}, {});
  ASSERT_TRUE(n.valves.has_value());
  for (double u : n.valves->opening()) EXPECT_EQ(u, 0.0);

  auto external = nodeFor(scenarioWith({"controller={type: external}"}));
  EXPECT_FALSE(external.commandsValves());
  EXPECT_FALSE(external.step(0, kDt, {}, {}).valves.has_value());
  // With a reservoir the external client has the valves; the engines stay on at full speed.
  EXPECT_TRUE(external.commandsEngines());
  EXPECT_EQ(external.step(0, kDt, {}, {}).engines->engines()[2].speed(), 1.0);
}

TEST(ControllerNode, ReferenceOpensValvesWhenSuctionIsShortAndClosesWhenItIsTooDeep) {
  auto node = nodeFor(scenarioWith({}));
  // Reservoir deep, chambers at ambient, F = 0: the valves open.
  auto weak = stateAt(100000.0);
  weak.pressure_pa()[7] = 80000.0;
  const auto opened = node.step(0, kDt, {weak}, {forceOf(0.0)});
  for (double u : opened.valves->opening()) EXPECT_GT(u, 0.0);
  // Chambers deeper than the set-point asks: the openings fall again.
  auto deep = stateAt(85000.0);
  deep.pressure_pa()[7] = 80000.0;
  double before = opened.valves->opening()[0];
  for (int k = 1; k < 50; ++k) node.step(k * kDt, kDt, {deep}, {forceOf(6000.0)});
  EXPECT_LT(node.step(50 * kDt, kDt, {deep}, {forceOf(6000.0)}).valves->opening()[0], before);
}

TEST(ControllerNode, DropsNonFiniteSamplesAndHoldsTheLastValid) {
  auto node = nodeFor(scenarioWith({}));
  node.step(0, kDt, {stateAt(95000.0)}, {forceOf(1000.0)});
  auto bad_state = stateAt(95000.0);
  bad_state.pressure_pa()[3] = std::numeric_limits<double>::quiet_NaN();
  node.step(kDt, kDt, {bad_state}, {forceOf(std::numeric_limits<double>::infinity())});
  EXPECT_EQ(node.droppedSamples(), 2u);
  EXPECT_EQ(node.heldMeasurement().pressure_pa[3], 95000.0);
  EXPECT_EQ(node.heldMeasurement().downforce_n, 1000.0);
}

}  // namespace
}  // namespace climbsim::controller
