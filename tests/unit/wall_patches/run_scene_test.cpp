// The scene of one run (run_scene.hpp): a scenario's crack generates the run's own pylon, which
// differs from the build's scene in the crack's block only; without a crack nothing is generated.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "climbsim/scenario.hpp"
#include "climbsim/run_prep/run_scene.hpp"
#include "surface_sampler.hpp"

namespace climbsim::surface {
namespace {
namespace fs = std::filesystem;

const std::string kScenario = R"(name: t
robot: ROBOT
scene: $BUILD/scenes/pylon.xml
start: {x_m: 1.0, y_m: 1.2, yaw_deg: -90}
duration_s: 1
controller: {type: reference}
drive:
  - {t_s: 0}
)";

/// Every file of the scene directory `dir`, relative to it.
std::vector<std::string> sceneFiles(const std::string& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) out.push_back(fs::relative(entry.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RunScene, ACrackGeneratesThePylonWithOnlyThatCrackChangedAndTheShippedOneByteForByte) {
  const test::ScopedTempDir scope("run_scene");
  const std::string scenario = scope.path + "/x.yaml";
  std::string text = kScenario;
  text.replace(text.find("ROBOT"), 5, std::string(CLIMBSIM_ROOT) + "/deploy/robots/cromsci.yaml");
  std::ofstream(scenario) << text;
  const std::string build_scene = std::string(CLIMBSIM_BUILD_DIR) + "/scenes";
  const std::vector<std::string> files = sceneFiles(build_scene);
  ASSERT_GE(files.size(), 14u) << "pylon.xml, the blocks' XML and 12 blocks";

  // Without a crack: the build's scene, nothing written.
  EXPECT_EQ(generateRunScene(loadScenario(scenario), scope.path + "/plain"), "");
  EXPECT_FALSE(fs::exists(scope.path + "/plain/scene"));

  // The shipped crack's values given explicitly: the build's scene, byte for byte.
  const std::string same = runScenarioText(scenario, {"crack={depth_m: 0.04, width_m: 0.01}"}, CLIMBSIM_BUILD_DIR,
                                           scope.path + "/same");
  EXPECT_NE(same.find("scene: " + scope.path + "/same/scene/pylon.xml"), std::string::npos) << same;
  ASSERT_EQ(sceneFiles(scope.path + "/same/scene"), files);
  for (const auto& f : files) {
    EXPECT_TRUE(test::readBytes(build_scene + "/" + f) == test::readBytes(scope.path + "/same/scene/" + f)) << f;
  }

  // A 5 mm crack: the crack's block (and the comment of pylon.xml naming it) differ, nothing else.
  runScenarioText(scenario, {"crack.depth_m=0.005"}, CLIMBSIM_BUILD_DIR, scope.path + "/shallow");
  ASSERT_EQ(sceneFiles(scope.path + "/shallow/scene"), files);
  for (const auto& f : files) {
    const bool changed = f == "meshes/block_c1_r0_crack.ply" || f == "pylon.xml";
    EXPECT_EQ(test::readBytes(build_scene + "/" + f) == test::readBytes(scope.path + "/shallow/scene/" + f), !changed)
        << f;
  }
  EXPECT_NE(test::readBytes(scope.path + "/shallow/scene/pylon.xml").find("5 mm deep"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::surface
