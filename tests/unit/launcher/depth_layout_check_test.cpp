#include "depth_layout_check.hpp"

#include <gtest/gtest.h>

#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {
namespace {

/// deploy/compose.hires-shards.yaml's depth services: two tile renderers, two shards, each
/// shard reading its own renderer.
const std::string kShards = R"(name: shards
clock: {duration_s: 1}
services:
  scene:   {command: [climbsim-scene, --scenario, "${scenario}", --outputs, depth, --tile, "${replica}/${replicas}"],
            period: 2, offset: 0, replicas: 2}
  sealing: {command: [climbsim-sealing, --scenario, "${scenario}", --shard, "${replica}/${replicas}",
                      --depth-from, "scene-${replica}"],
            period: 2, offset: 1, replicas: 2}
  thermo:  {command: [climbsim-thermo, --scenario, "${scenario}"]}
)";

/// The scenario's scene: a 256 px depth camera `width_m` wide (0: no size, the robot's view).
scene::SceneDescription sceneWithCamera(double width_m = 0.8) {
  scene::SceneDescription description;
  description.file = "scene.xml";
  scene::CameraInfo camera;
  camera.name = "depth_cam";
  camera.width_px = 256;
  camera.height_px = 256;
  camera.width_m = width_m;
  camera.near_limit_m = -0.05;
  camera.far_limit_m = 0.05;
  description.cameras.push_back(camera);
  return description;
}

/// A scenario of the default robot at its default image size.
Scenario ofCromsci() {
  Scenario scenario;
  scenario.robot_file = "cromsci";
  return scenario;
}

Scenario hires() {
  Scenario scenario = ofCromsci();
  scenario.depth_camera.size_px = 1024;
  return scenario;
}

/// kShards with `from` replaced by `to` (which must occur).
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// The one-line error of checking `compose_text`, or "" if it passes.
std::string errorOf(const std::string& compose_text, const Scenario& scenario = hires(),
                    const scene::SceneDescription& scene = sceneWithCamera()) {
  try {
    checkDepthLayout(parseComposeText(compose_text, "c.yaml"), scenario, scene);
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("c.yaml:", 0), 0u) << message;
    return message;
  }
  return "";
}

TEST(DepthLayoutCheck, ShippedLayoutsPass) {
  EXPECT_EQ(errorOf(kShards), "");
  // Without --depth-from each shard reads every tile, its own among them.
  EXPECT_EQ(errorOf(with(kShards, R"(--depth-from, "scene-${replica}")", "--images, \"0\"")), "");
  // One renderer of the whole image for every shard.
  EXPECT_EQ(errorOf(with(with(kShards, R"(--tile, "${replica}/${replicas}"],
            period: 2, offset: 0, replicas: 2})",
                              "--tile, \"0/1\"],\n            period: 2, offset: 0}"),
                         R"(--depth-from, "scene-${replica}")", "--depth-from, scene")),
            "");
}

TEST(DepthLayoutCheck, ATileLayoutThatMissesAShardIsNamed) {
  const std::string message = errorOf(with(kShards, R"(--tile, "${replica}/${replicas}")", "--tile, \"0/2\""));
  EXPECT_NE(message.find("services.sealing (sealing-1)"), std::string::npos) << message;
  EXPECT_NE(message.find("shard 1/2 reads scene-1 --tile 0/2"), std::string::npos) << message;
  // Tiles of another count than the shards'.
  const std::string thirds = errorOf(with(kShards, R"(--tile, "${replica}/${replicas}")", "--tile, \"${replica}/3\""));
  EXPECT_NE(thirds.find("services.sealing (sealing-0): shard 0/2 reads scene-0 --tile 0/3"), std::string::npos) << thirds;
}

TEST(DepthLayoutCheck, ShardsAndRenderersThatDisagreeOnTheImageAreNamed) {
  const std::string px = errorOf(with(kShards, "--shard, \"${replica}/${replicas}\"",
                                      "--shard, \"${replica}/${replicas}\", --camera-px, \"512\""));
  EXPECT_NE(px.find("services.sealing (sealing-0): reads a depth image of 512 x 512 px"), std::string::npos) << px;
  EXPECT_NE(px.find("'scene-0'"), std::string::npos) << px;
  EXPECT_NE(px.find("renders 1024 x 1024 px"), std::string::npos) << px;
  const std::string view = errorOf(with(kShards, "--shard, \"${replica}/${replicas}\"",
                                        "--shard, \"${replica}/${replicas}\", --view-m, \"0.4\""));
  EXPECT_NE(view.find("of 0.390625 mm"), std::string::npos) << view;
  // Without a scenario on its command line a renderer takes the scene camera's 256 px.
  const std::string own = errorOf(with(kShards, "[climbsim-scene, --scenario, \"${scenario}\",", "[climbsim-scene,"));
  EXPECT_NE(own.find("renders 256 x 256 px"), std::string::npos) << own;
}

TEST(DepthLayoutCheck, ADepthFromThatIsNoRendererIsNamed) {
  const std::string message = errorOf(with(kShards, "\"scene-${replica}\"", "\"scene-7\""));
  EXPECT_NE(message.find("--depth-from scene-7: no service instance of this compose file has that name (depth "
                         "renderers: scene-0, scene-1)"),
            std::string::npos)
      << message;
  // Another program's instance may write depth images (a test feeder): the clock checks it.
  EXPECT_EQ(errorOf(with(kShards, "\"scene-${replica}\"", "thermo")), "");
}

/// One renderer and one sealing, both of the scenario.
const std::string kPlain = R"(name: plain
clock: {duration_s: 1}
services:
  scene:   {command: [climbsim-scene, --scenario, "${scenario}"], period: 2, offset: 0}
  sealing: {command: [climbsim-sealing, --scenario, "${scenario}"], period: 2, offset: 1}
)";

TEST(DepthLayoutCheck, OneRendererAndOneSealingAtTheScenariosSizePass) {
  const std::string plain = kPlain;
  EXPECT_EQ(errorOf(plain), "");
  EXPECT_EQ(errorOf(plain, ofCromsci()), "");  // both at the camera's and the default 256 px
  const std::string message = errorOf(with(plain, "[climbsim-scene, --scenario, \"${scenario}\"",
                                           "[climbsim-scene, --scenario, \"${scenario}\", --depth-size-px, \"512\""));
  EXPECT_NE(message.find("services.sealing: reads a depth image of 1024 x 1024 px"), std::string::npos) << message;
}

TEST(DepthLayoutCheck, BothSidesTakeTheRobotsViewAndASceneSizeThatDiffersIsNamed) {
  Scenario ring = ofCromsci();
  ring.robot_file = "ring-12";  // 1 m across: a 1.0 m view
  EXPECT_EQ(errorOf(kPlain, ring, sceneWithCamera(0.0)), "");
  EXPECT_EQ(errorOf(kPlain, ofCromsci(), sceneWithCamera(0.0)), "");
  // The scene's own 0.8 m camera wins for the renderer; the sealing must be told the same.
  const std::string message = errorOf(kPlain, ring);
  EXPECT_NE(message.find("services.sealing: reads a depth image of 256 x 256 px of 3.90625 mm"), std::string::npos)
      << message;
  EXPECT_NE(message.find("renders 256 x 256 px of 3.125 mm"), std::string::npos) << message;
  EXPECT_EQ(errorOf(with(kPlain, "[climbsim-sealing, --scenario, \"${scenario}\"",
                         "[climbsim-sealing, --scenario, \"${scenario}\", --view-m, \"0.8\""),
                    ring),
            "");
}

}  // namespace
}  // namespace climbsim::launcher
