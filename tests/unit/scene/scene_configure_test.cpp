// climbsim-scene's one configuration path (services/scene/configure.hpp): its main, climbsim
// solo and the launcher's depth layout check take the scene file and the model's parameters
// from configureScene and sceneParams; each option changes the value it names.

#include <gtest/gtest.h>

#include <string>

#include "climbsim/errors.hpp"
#include "scene/configure.hpp"

namespace climbsim::scene {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;
const std::string kBuild = "/the/build";

TEST(SceneConfigure, TheScenarioGivesTheSceneAndTheImageSize) {
  const ScenarioAndRobot hires = loadScenarioAndRobot(kScenarios + "/crack-descent-hires.yaml", {});
  const SceneSetup setup = configureScene(hires, {}, kBuild);
  EXPECT_EQ(setup.scene_file, kBuild + "/scenes/pylon.xml");
  EXPECT_EQ(setup.robot_file, hires.scenario->robotPath());
  EXPECT_EQ(setup.params.depth_size_px, std::optional<int>(1024));
  EXPECT_TRUE(setup.write_depth);
  EXPECT_TRUE(setup.write_laser);
  // The scenario's default (size 0): the scene camera's size.
  const ScenarioAndRobot plain = loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {});
  EXPECT_EQ(configureScene(plain, {}, kBuild).params.depth_size_px, std::nullopt);
}

// depth_camera.subpixel (on by default): area-weighted edge pixels and their support heights
// here (and sub-pixel strip shares for a --tile's shard, as in the sealing); one ray per pixel
// centre with it off or without a scenario.
TEST(SceneConfigure, TheScenariosSubpixelOptionAveragesRaysOverEdgePixels) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  const SceneSetup plain = configureScene(loadScenarioAndRobot(file, {"depth_camera.subpixel=false"}), {}, kBuild);
  EXPECT_EQ(plain.params.depth_samples_per_pixel, 1);
  EXPECT_FALSE(plain.subpixel);
  const SceneSetup by_default = configureScene(loadScenarioAndRobot(file, {}), {}, kBuild);
  EXPECT_EQ(by_default.params.depth_samples_per_pixel, kSubpixelDepthSamplesPerPixel);
  EXPECT_TRUE(by_default.subpixel);
  const SceneSetup on = configureScene(loadScenarioAndRobot(file, {"depth_camera.subpixel=true"}), {}, kBuild);
  EXPECT_EQ(on.params.depth_samples_per_pixel, kSubpixelDepthSamplesPerPixel);
  EXPECT_TRUE(on.subpixel);
  // Support heights for the robot's sealing slope, as the sealing adapts with it.
  const ScenarioAndRobot run_on = loadScenarioAndRobot(file, {"depth_camera.subpixel=true"});
  EXPECT_EQ(on.params.depth_support_slope, run_on.robot.sealing.max_slope);
  EXPECT_GT(on.params.depth_support_slope, 0.0);
  EXPECT_EQ(plain.params.depth_support_slope, 0.0);
  const SceneSetup off = configureScene(loadScenarioAndRobot(file, {"depth_camera.subpixel=false"}), {}, kBuild);
  EXPECT_EQ(off.params.depth_samples_per_pixel, 1);
  EXPECT_FALSE(off.subpixel);
  EXPECT_EQ(sceneParams(loadScenarioAndRobot("", {}), {}).depth_samples_per_pixel, 1);
  try {
    loadScenarioAndRobot(file, {"depth_camera.subpixel=often"});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("depth_camera.subpixel"), std::string::npos) << e.what();
  }
}

// The image's side on the wall defaults to the robot's view: the default robot's 0.8 m, a
// larger robot's more; --depth-width-m and a scene camera's size come first.
TEST(SceneConfigure, TheRobotGivesTheDefaultViewAndTheSceneCameraOrOptionWin) {
  const ScenarioAndRobot cromsci = loadScenarioAndRobot(kScenarios + "/crack-descent.yaml", {});
  EXPECT_EQ(sceneParams(cromsci, {}).robot_view_m, std::optional<double>(0.8));
  const ScenarioAndRobot ring = loadScenarioAndRobot(kScenarios + "/hold-ring-12.yaml", {});
  EXPECT_EQ(sceneParams(ring, {}).robot_view_m, std::optional<double>(1.0));

  SceneDescription scene;
  scene.file = "test.xml";
  CameraInfo camera;
  camera.name = "depth_cam";
  camera.width_px = 256;
  camera.near_limit_m = -0.05;
  camera.far_limit_m = 0.05;
  scene.cameras.push_back(camera);
  EXPECT_DOUBLE_EQ(depthCameraParams(scene, sceneParams(ring, {})).pixel_size_m, 1.0 / 256);
  EXPECT_EQ(depthCameraParams(scene, sceneParams(cromsci, {})).pixel_size_m, 0.8 / 256);
  SceneOverrides width;
  width.depth_width_m = 0.6;
  EXPECT_DOUBLE_EQ(depthCameraParams(scene, sceneParams(ring, width)).pixel_size_m, 0.6 / 256);
  scene.cameras.front().width_m = 1.2;  // the scene's own size
  EXPECT_DOUBLE_EQ(depthCameraParams(scene, sceneParams(ring, {})).pixel_size_m, 1.2 / 256);
  EXPECT_DOUBLE_EQ(depthCameraParams(scene, sceneParams(ring, width)).pixel_size_m, 0.6 / 256);
}

TEST(SceneConfigure, WithoutAScenarioTheOptionsAndSceneParamsDefaults) {
  const ScenarioAndRobot none = loadScenarioAndRobot("", {});
  const SceneSetup setup = configureScene(none, {}, kBuild);
  const SceneParams defaults;
  EXPECT_FALSE(setup.scene_file.empty());
  EXPECT_EQ(setup.robot_file, "");
  EXPECT_EQ(setup.params.robot_view_m, std::optional<double>(0.8)) << "the default robot's view";
  EXPECT_EQ(setup.params.pose_element, defaults.pose_element);
  EXPECT_EQ(setup.params.camera, defaults.camera);
  EXPECT_EQ(setup.params.laser, defaults.laser);
  EXPECT_EQ(setup.params.backend, defaults.backend);
  SceneOverrides own;
  own.scene_file = "/my/scene.xml";
  EXPECT_EQ(configureScene(none, own, kBuild).scene_file, "/my/scene.xml");
}

TEST(SceneConfigure, EachOptionChangesTheValueItNames) {
  const ScenarioAndRobot hires = loadScenarioAndRobot(kScenarios + "/crack-descent-hires.yaml", {});
  const SceneParams base = sceneParams(hires, {});
  SceneOverrides o;
  o.depth_size_px = 512;  // before the scenario's 1024
  EXPECT_EQ(sceneParams(hires, o).depth_size_px, std::optional<int>(512));
  o = {};
  o.depth_width_m = 0.6;
  EXPECT_EQ(sceneParams(hires, o).depth_width_m, std::optional<double>(0.6));
  EXPECT_EQ(sceneParams(hires, o).depth_size_px, base.depth_size_px);
  o = {};
  o.near_m = 0.04;
  o.far_m = -0.04;
  EXPECT_EQ(sceneParams(hires, o).near_m, std::optional<double>(0.04));
  EXPECT_EQ(sceneParams(hires, o).far_m, std::optional<double>(-0.04));
  o = {};
  o.backend = "embree";
  EXPECT_EQ(sceneParams(hires, o).backend, DepthBackend::kEmbree);
  o = {};
  o.camera = "";
  EXPECT_EQ(sceneParams(hires, o).camera, "");
  EXPECT_EQ(sceneParams(hires, o).laser, base.laser);
  // --outputs depth (compose.yaml's, and climbsim solo's): no laser.
  o = {};
  o.outputs = "depth";
  const SceneSetup depth_only = configureScene(hires, o, kBuild);
  EXPECT_TRUE(depth_only.write_depth);
  EXPECT_FALSE(depth_only.write_laser);
  EXPECT_EQ(depth_only.params.laser, "");
  EXPECT_EQ(depth_only.params.depth_size_px, base.depth_size_px);
}

TEST(SceneConfigure, BadOptionsAreNamed) {
  const ScenarioAndRobot none = loadScenarioAndRobot("", {});
  SceneOverrides o;
  o.backend = "raytracer";
  EXPECT_THROW(sceneParams(none, o), ConfigError);
  o = {};
  o.outputs = "depth,sonar";
  EXPECT_THROW(configureScene(none, o, kBuild), ConfigError);
}

TEST(SceneConfigure, AScenarioRunRendersTheSealingsPixelsButTheFramesReadWhole) {
  const std::string file = kScenarios + "/crack-descent.yaml";
  const ScenarioAndRobot run = loadScenarioAndRobot(file, {});
  const SceneSetup setup = configureScene(run, {}, kBuild);
  EXPECT_TRUE(setup.frames.masked());
  EXPECT_EQ(setup.frames.robot_file, setup.robot_file);
  EXPECT_EQ(setup.frames.read_at_s, run.scenario->pictures.sealing_at_s) << "the sealing pictures' frames are whole";
  EXPECT_EQ(setup.frames.read_lag_ns, run.scenario->step_ns) << "the sealing reads a frame one clock step later";
  EXPECT_FALSE(setup.frames.every_frame_whole);
  EXPECT_TRUE(configureScene(loadScenarioAndRobot(file, {"depth_camera.subpixel=true"}), {}, kBuild).frames.subpixel);
  // run.mcap's every depth image: every frame whole.
  const SceneSetup recorded = configureScene(loadScenarioAndRobot(file, {"recording.depth_images=true"}), {}, kBuild);
  EXPECT_TRUE(recorded.frames.every_frame_whole);
  EXPECT_FALSE(recorded.frames.masked());
  // Without a scenario (no sealing known), on Embree (no masks) or without depth: every frame whole.
  EXPECT_FALSE(configureScene(loadScenarioAndRobot("", {}), {}, kBuild).frames.masked());
  SceneOverrides embree;
  embree.backend = "embree";
  EXPECT_FALSE(configureScene(run, embree, kBuild).frames.masked());
  SceneOverrides laser_only;
  laser_only.outputs = "laser";
  EXPECT_FALSE(configureScene(run, laser_only, kBuild).frames.masked());
}

}  // namespace
}  // namespace climbsim::scene
