// climbsim-controller's one configuration path (services/controller/configure.hpp): its main
// (and --print-config) and climbsim solo both take the command model's parameters from
// configureController; they are the scenario's controller section and drive schedule with the
// robot's controller parameters.

#include <gtest/gtest.h>

#include <string>

#include "climbsim/errors.hpp"
#include "controller/configure.hpp"

namespace climbsim::controller {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;

TEST(ControllerConfigure, MainAndSoloGetTheSameParamsFromAScenario) {
  for (const char* name : {"crack-descent", "valve-stuck", "figure9"}) {
    const std::string file = kScenarios + "/" + name + ".yaml";
    const ControllerParams main_params = configureController(loadScenarioAndRobot(file, {}));
    const ControllerParams solo_params = configureController(scenarioAndRobot(loadScenario(file)));
    EXPECT_EQ(main_params.kind, solo_params.kind) << name;
    EXPECT_EQ(main_params.engine_count, solo_params.engine_count) << name;
    EXPECT_EQ(main_params.drive.size(), solo_params.drive.size()) << name;
    EXPECT_EQ(main_params.reference.desired_downforce_n, solo_params.reference.desired_downforce_n) << name;
  }
}

TEST(ControllerConfigure, TheScenariosControllerAndScheduleAnOverrideChangesItsKey) {
  const std::string file = kScenarios + "/crack-descent.yaml";  // reference at 2200 N, two drive entries
  const ScenarioAndRobot run = loadScenarioAndRobot(file, {});
  const ControllerParams params = configureController(run);
  EXPECT_EQ(params.kind, Scenario::ControllerKind::kReference);
  EXPECT_EQ(params.reference.desired_downforce_n, 2200.0);
  ASSERT_EQ(params.drive.size(), 2u);
  EXPECT_EQ(params.drive[1].vx_mps, 0.05);
  const ControllerParams lower = configureController(loadScenarioAndRobot(file, {"controller.downforce_n=1800"}));
  EXPECT_EQ(lower.reference.desired_downforce_n, 1800.0);
  EXPECT_EQ(lower.kind, params.kind);
  EXPECT_EQ(lower.drive.size(), params.drive.size());
  EXPECT_EQ(lower.engine_count, params.engine_count);
}

TEST(ControllerConfigure, AScenarioIsNeeded) {
  EXPECT_THROW(configureController(loadScenarioAndRobot("", {})), ConfigError);
}

}  // namespace
}  // namespace climbsim::controller
