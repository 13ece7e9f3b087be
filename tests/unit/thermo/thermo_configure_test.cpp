// climbsim-thermo's one configuration path (services/thermo/configure.hpp): its main and
// climbsim solo both take the model's parameters from configureThermo; they are the robot's,
// with the scenario's plant faults.

#include <gtest/gtest.h>

#include <string>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"
#include "thermo/configure.hpp"

namespace climbsim::thermo {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;

TEST(ThermoConfigure, MainAndSoloGetTheSameSetupFromAScenario) {
  for (const char* name : {"valve-stuck", "engine-failure", "crack-descent"}) {
    const std::string file = kScenarios + "/" + name + ".yaml";
    const ThermoSetup main_setup = configureThermo(loadScenarioAndRobot(file, {}));
    const ThermoSetup solo_setup = configureThermo(scenarioAndRobot(loadScenario(file)));
    ASSERT_EQ(main_setup.params.faults.size(), solo_setup.params.faults.size()) << name;
    for (std::size_t i = 0; i < main_setup.params.faults.size(); ++i) {
      EXPECT_EQ(main_setup.params.faults[i].t_ns, solo_setup.params.faults[i].t_ns) << name;
    }
    EXPECT_EQ(main_setup.segment_names, solo_setup.segment_names) << name;
    EXPECT_EQ(main_setup.basic_leak_area_m2, solo_setup.basic_leak_area_m2) << name;
    EXPECT_EQ(main_setup.params.engines.size(), solo_setup.params.engines.size()) << name;
  }
}

TEST(ThermoConfigure, TheRobotsParametersWithTheScenariosFaults) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/valve-stuck.yaml", {});
  const ThermoSetup setup = configureThermo(run);
  const ThermoParams robot = thermoParamsFromRobot(run.robot, run.geometry);
  EXPECT_EQ(setup.params.engines.size(), robot.engines.size());
  EXPECT_EQ(setup.params.segments.size(), robot.segments.size());
  ASSERT_EQ(setup.params.faults.size(), 1u);  // valve_stuck: chamber 3 at 0.5 from 6 s
  EXPECT_EQ(setup.params.faults[0].kind, PlantFault::Kind::kValveStuck);
  EXPECT_EQ(setup.params.faults[0].chamber, 3);
  EXPECT_EQ(setup.params.faults[0].opening, 0.5);
  EXPECT_EQ(setup.params.faults[0].t_ns, 6'000'000'000);
  EXPECT_EQ(setup.segment_names, segmentNames(run.geometry));
  EXPECT_TRUE(setup.inputs.leakage && setup.inputs.valves && setup.inputs.engines);
  // Without a scenario: no faults.
  EXPECT_TRUE(configureThermo(loadScenarioAndRobot("", {})).params.faults.empty());
}

TEST(ThermoConfigure, TheInputsOptionChangesTheInputsOnly) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/valve-stuck.yaml", {});
  ThermoOverrides o;
  o.inputs = "leakage";
  const ThermoSetup setup = configureThermo(run, o);
  EXPECT_TRUE(setup.inputs.leakage);
  EXPECT_FALSE(setup.inputs.valves);
  EXPECT_FALSE(setup.inputs.engines);
  EXPECT_EQ(setup.params.faults.size(), 1u);
  o.inputs = "leakage,pumps";
  EXPECT_THROW(configureThermo(run, o), ConfigError);
}

}  // namespace
}  // namespace climbsim::thermo
