// climbsim-sealing's one configuration path (services/sealing/configure.hpp): its main,
// climbsim solo and the launcher's depth layout check take the camera and the setup from
// configureSealing and sealingCamera; the values are the scenario's and the robot's, and each
// option changes the value it names.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"
#include "sealing/configure.hpp"

namespace climbsim::sealing {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;
const std::string kRobots = CLIMBSIM_ROBOTS_DIR;

TEST(SealingConfigure, MainAndSoloGetTheSameSetupFromAScenario) {
  for (const char* name : {"crack-descent", "crack-descent-hires", "hole-under-chamber"}) {
    const std::string file = kScenarios + "/" + name + ".yaml";
    const SealingSetup main_setup = configureSealing(loadScenarioAndRobot(file, {}));
    const SealingSetup solo_setup = configureSealing(scenarioAndRobot(loadScenario(file)));
    EXPECT_EQ(main_setup.camera, solo_setup.camera) << name;
    EXPECT_EQ(main_setup.params.segment_names, solo_setup.params.segment_names) << name;
    EXPECT_EQ(main_setup.params.basic_gap_m, solo_setup.params.basic_gap_m) << name;
    EXPECT_EQ(main_setup.picture_times, solo_setup.picture_times) << name;
    EXPECT_EQ(main_setup.end_on_seal_over_nothing, solo_setup.end_on_seal_over_nothing) << name;
  }
}

TEST(SealingConfigure, TheScenariosCameraElseTheDefaultCamera) {
  const ScenarioAndRobot hires = loadScenarioAndRobot(kScenarios + "/crack-descent-hires.yaml", {});
  const SealingSetup setup = configureSealing(hires);
  EXPECT_EQ(setup.camera.width_px, 1024);
  EXPECT_EQ(setup.camera.height_px, 1024);
  EXPECT_DOUBLE_EQ(setup.camera.pixel_size_m, 0.8 / 1024);
  EXPECT_EQ(setup.picture_times, hires.scenario->pictures.sealing_at_s);
  EXPECT_EQ(setup.shard.index, 0u);
  EXPECT_EQ(setup.shard.count, 1u);
  const ScenarioAndRobot plain = loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {});
  EXPECT_EQ(configureSealing(plain).camera, (PixelGrid{kDefaultCameraPx, kDefaultCameraPx, 0.8 / 256}));
  // Without a scenario: the default robot's view.
  EXPECT_EQ(sealingCamera(loadScenarioAndRobot("", {}), {}), (PixelGrid{256, 256, 0.80 / 256}));
}

// depth_camera.subpixel (on by default): the strips' sub-pixel shares (as the scene's
// area-weighted edge pixels); their pixel centres with it off or without a scenario.
TEST(SealingConfigure, TheScenariosSubpixelOptionOutlinesTheStripsBySubpixelShares) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  EXPECT_EQ(configureSealing(loadScenarioAndRobot(file, {})).params.strip_outline, StripOutline::kSubpixelShares);
  EXPECT_EQ(configureSealing(loadScenarioAndRobot(file, {"depth_camera.subpixel=false"})).params.strip_outline,
            StripOutline::kPixelCentres);
  const SealingSetup on = configureSealing(loadScenarioAndRobot(file, {"depth_camera.subpixel=true"}));
  EXPECT_EQ(on.params.strip_outline, StripOutline::kSubpixelShares);
  EXPECT_EQ(configureSealing(scenarioAndRobot(loadScenario(file, {"depth_camera.subpixel=true"}))).params.strip_outline,
            StripOutline::kSubpixelShares);
  EXPECT_EQ(configureSealing(loadScenarioAndRobot("", {})).params.strip_outline, StripOutline::kPixelCentres);
}

// The default view follows the robot: every shipped robot's strips fit the image the sealing
// reads (StripMasks refuses a strip outside it), the default robot keeps 256 px over 0.8 m, a
// robot larger than 0.8 m gets a larger view, and an explicit view that is too small is one
// line naming the strip.
TEST(SealingConfigure, EveryShippedRobotsViewHoldsItsStrips) {
  int robots = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kRobots)) {
    if (entry.path().extension() != ".yaml") continue;
    ++robots;
    const ScenarioAndRobot run = loadScenarioAndRobot("", {}, entry.path().string());
    const SealingSetup setup = configureSealing(run);
    EXPECT_NO_THROW(StripMasks(run.geometry, setup.camera, run.robot_file)) << entry.path();
    EXPECT_EQ(setup.camera.width_px, kDefaultCameraPx) << entry.path();
    EXPECT_DOUBLE_EQ(setup.view_m, setup.camera.pixel_size_m * setup.camera.width_px) << entry.path();
  }
  EXPECT_GE(robots, 4);

  const SealingSetup cromsci = configureSealing(loadScenarioAndRobot("", {}, kRobots + "/cromsci.yaml"));
  EXPECT_EQ(cromsci.view_m, 0.8);
  EXPECT_EQ(cromsci.camera, (PixelGrid{256, 256, 0.8 / 256}));

  const ScenarioAndRobot ring = loadScenarioAndRobot("", {}, kRobots + "/ring-12.yaml");
  ASSERT_GT(ring.robot.body.outerRadius() * 2.0, 0.8) << "a robot larger than 0.8 m";
  const SealingSetup large = configureSealing(ring);
  EXPECT_EQ(large.view_m, 1.0);
  EXPECT_NO_THROW(StripMasks(ring.geometry, large.camera, ring.robot_file));
  SealingOverrides small;
  small.view_m = 0.8;
  try {
    StripMasks(ring.geometry, configureSealing(ring, small).camera, ring.robot_file);
    ADD_FAILURE() << "0.8 m holds ring-12's strips";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the camera's view of 0.8 x 0.8 m"), std::string::npos) << e.what();
  }
}

TEST(SealingConfigure, EachOptionChangesTheValueItNames) {
  const ScenarioAndRobot run = loadScenarioAndRobot(kScenarios + "/crack-descent-hires.yaml", {});
  const SealingSetup base = configureSealing(run);
  SealingOverrides px;
  px.camera_px = 512;  // before the scenario's 1024
  EXPECT_EQ(configureSealing(run, px).camera, (PixelGrid{512, 512, 0.8 / 512}));
  SealingOverrides view;
  view.view_m = 0.4;
  const SealingSetup viewed = configureSealing(run, view);
  EXPECT_EQ(viewed.camera, (PixelGrid{1024, 1024, 0.4 / 1024}));
  EXPECT_EQ(viewed.view_m, 0.4);
  EXPECT_EQ(viewed.picture_times, base.picture_times);
  SealingOverrides shard;
  shard.shard = "1/2";
  const SealingSetup second = configureSealing(run, shard);
  EXPECT_EQ(second.shard.index, 1u);
  EXPECT_EQ(second.camera, base.camera);
  EXPECT_TRUE(second.picture_times.empty()) << "shard 0 keeps the pictures";
  SealingOverrides bad;
  bad.view_m = 0.0;
  EXPECT_THROW(configureSealing(run, bad), ConfigError);
}

TEST(SealingConfigure, EndOnSealOverNothingIsTheScenarios) {
  EXPECT_FALSE(configureSealing(loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {})).end_on_seal_over_nothing);
  const Scenario ends = parseScenarioText(
      "name: ends\nrobot: ../robots/cromsci.yaml\nscene: $BUILD/scenes/pylon.xml\nstart: {x_m: 1, y_m: 1}\n"
      "duration_s: 1\ncontroller: {type: none}\n"
      "drive:\n  - {t_s: 0}\nend_on: {seal_over_nothing: true}\n",
      kScenarios + "/ends.yaml");
  EXPECT_TRUE(configureSealing(scenarioAndRobot(ends)).end_on_seal_over_nothing);
}

}  // namespace
}  // namespace climbsim::sealing
