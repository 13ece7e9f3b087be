// climbsim-recorder's one configuration path (services/recorder/configure.hpp): its main and
// climbsim solo both take the trace's columns and statistics, the label and the pictures from
// configureRecorder.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "climbsim/errors.hpp"
#include "recorder/configure.hpp"

namespace climbsim::recorder {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;

TEST(RecorderConfigure, MainAndSoloGetTheSameSetupFromAScenario) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  RecorderSetup main_setup = configureRecorder(loadScenarioAndRobot(file, {}));
  RecorderSetup solo_setup = configureRecorder(scenarioAndRobot(loadScenario(file)));
  EXPECT_EQ(main_setup.trace.columns(), solo_setup.trace.columns());
  EXPECT_EQ(main_setup.trace.summary(), solo_setup.trace.summary());
  EXPECT_EQ(main_setup.label, solo_setup.label);
  EXPECT_EQ(main_setup.picture_times, solo_setup.picture_times);
  EXPECT_EQ(main_setup.depth_period_ns, solo_setup.depth_period_ns);
}

TEST(RecorderConfigure, TheScenariosLabelHoldSlideLimitAndPictures) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {"slide_limit_m=0.01"});
  const RecorderSetup setup = configureRecorder(run);
  EXPECT_EQ(setup.label, "crack-descent");
  EXPECT_EQ(setup.picture_times, run.scenario->pictures.sealing_at_s);
  EXPECT_EQ(setup.depth_period_ns, 20'000'000);  // depth_hz 50
  const auto summary = setup.trace.summary();
  EXPECT_DOUBLE_EQ(summary["downforce_from_s"].get<double>(), 2.0);  // start.hold_s
  EXPECT_DOUBLE_EQ(summary["slide_limit_m"].get<double>(), 0.01);
  RecorderOverrides labelled;
  labelled.label = "mine";
  EXPECT_EQ(configureRecorder(run, labelled).label, "mine");
  EXPECT_EQ(configureRecorder(run, labelled).picture_times, setup.picture_times);
  // Without a scenario: no label, no pictures.
  const RecorderSetup bare = configureRecorder(loadScenarioAndRobot("", {}));
  EXPECT_EQ(bare.label, "");
  EXPECT_TRUE(bare.picture_times.empty());
  EXPECT_EQ(bare.trace.columns(), setup.trace.columns());
}

TEST(RecorderConfigure, TheScenariosRecordingDepthImagesAddsEveryDepthImage) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  EXPECT_FALSE(configureRecorder(loadScenarioAndRobot(file, {})).inputs.depth_images) << "off by default";
  EXPECT_TRUE(configureRecorder(loadScenarioAndRobot(file, {"recording.depth_images=true"})).inputs.depth_images);
  EXPECT_THROW(loadScenarioAndRobot(file, {"recording.depth_images=often"}), ConfigError);
  EXPECT_THROW(loadScenarioAndRobot(file, {"recording.images=true"}), ConfigError);
}

TEST(RecorderConfigure, TheInputsOptionNamesTheTopicsRecorded) {
  const ScenarioAndRobot run = loadScenarioAndRobot("", {});
  const auto recorded = [&](const std::string& list) {
    RecorderOverrides o;
    o.inputs = list;
    const RecordedInputs in = configureRecorder(run, o).inputs;
    return std::vector<bool>{in.chamber, in.adhesion, in.leakage, in.robot, in.drive};
  };
  EXPECT_EQ(recorded("chamber,adhesion,leakage,robot,drive"), std::vector<bool>(5, true));
  EXPECT_EQ(recorded("robot,drive"), (std::vector<bool>{false, false, false, true, true}));
  EXPECT_EQ(recorded("none"), std::vector<bool>(5, false));
  EXPECT_THROW(recorded("sonar"), ConfigError);
}

}  // namespace
}  // namespace climbsim::recorder
