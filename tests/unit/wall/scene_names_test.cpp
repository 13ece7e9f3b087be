// Insertion points: full names, short names, nested scene files with relative paths.

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "climbsim/wall/scene.hpp"
#include "scene_test_files.hpp"

namespace climbsim::scene {
namespace {

std::vector<std::string> fullNames(const Scene& scene) {
  std::vector<std::string> out;
  for (const auto& p : scene.parts()) out.push_back(p.full_name);
  return out;
}

TEST(SceneNames, FullNamesFollowTheInsertionPoints) {
  testing::TempDir dir;
  const auto file = dir.write("s.xml", testing::sceneXml(R"(
  <part name="WORLD" attached_to="ROOT"/>
  <part name="ROBOT" attached_to="ROOT:WORLD" offset="0 0 1 0 0 0"/>
  <part name="DRIVE_FRONT" attached_to="ROBOT" offset="1 0 0 0 0 0"/>
  <part name="WHEEL" attached_to="ROOT:WORLD:ROBOT:DRIVE_FRONT" offset="0 1 0 0 0 0"/>
)"));
  const Scene scene = loadScene(file);
  EXPECT_EQ(fullNames(scene), (std::vector<std::string>{"ROOT", "ROOT:WORLD", "ROOT:WORLD:ROBOT",
                                                        "ROOT:WORLD:ROBOT:DRIVE_FRONT",
                                                        "ROOT:WORLD:ROBOT:DRIVE_FRONT:WHEEL"}));
  // Short and full names address the same part.
  EXPECT_EQ(scene.partIndex("WHEEL"), scene.partIndex("ROOT:WORLD:ROBOT:DRIVE_FRONT:WHEEL"));
  EXPECT_LT((scene.worldPose("WHEEL").translation() - Eigen::Vector3d(1, 1, 1)).norm(), 1e-12);
}

TEST(SceneNames, PartsMayBeAttachedToPartsDeclaredLater) {
  testing::TempDir dir;
  const auto file = dir.write("s.xml", testing::sceneXml(R"(
  <part name="TOOL" attached_to="ROOT:ARM" offset="0 0 2 0 0 0"/>
  <part name="ARM" attached_to="ROOT" offset="3 0 0 0 0 0"/>
)"));
  const Scene scene = loadScene(file);
  EXPECT_EQ(scene.parts()[scene.partIndex("TOOL")].full_name, "ROOT:ARM:TOOL");
  EXPECT_LT((scene.worldPose("TOOL").translation() - Eigen::Vector3d(3, 0, 2)).norm(), 1e-12);
}

TEST(SceneNames, UnaddressedDuplicatesAreFineAddressedOnesNeedTheFullName) {
  testing::TempDir dir;
  const auto file = dir.write("s.xml", testing::sceneXml(R"(
  <part name="LEFT" attached_to="ROOT" offset="-1 0 0 0 0 0"/>
  <part name="RIGHT" attached_to="ROOT" offset="1 0 0 0 0 0"/>
  <part name="BOLT" attached_to="LEFT" offset="0 1 0 0 0 0"/>
  <part name="BOLT" attached_to="RIGHT" offset="0 2 0 0 0 0"/>
  <part name="NUT" attached_to="ROOT:RIGHT:BOLT" offset="0 0 1 0 0 0"/>
)"));
  const Scene scene = loadScene(file);
  EXPECT_LT((scene.worldPose("NUT").translation() - Eigen::Vector3d(1, 2, 1)).norm(), 1e-12);
  EXPECT_THROW(scene.partIndex("BOLT"), ConfigError);

  const auto ambiguous = dir.write("a.xml", testing::sceneXml(R"(
  <part name="LEFT" attached_to="ROOT"/>
  <part name="BOLT" attached_to="LEFT"/>
  <part name="BOLT" attached_to="ROOT"/>
  <part name="NUT" attached_to="BOLT"/>
)"));
  try {
    loadScene(ambiguous);
    FAIL() << "an ambiguous short name loaded";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("a.xml:6:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("attached_to=\"BOLT\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ambiguous"), std::string::npos) << e.what();
  }
}

TEST(SceneNames, NestedFilesInsertTheirPartsUnderTheIncludingPartWithRelativePaths) {
  testing::TempDir dir;
  // top.xml -> walls/pylon.xml (twice) -> ../meshes/cube.ply and blocks/block.xml ->
  // ../../meshes/cube.ply: every relative path resolved against its own file's directory.
  dir.write("meshes/cube.ply", testing::asPly(testing::square(2.0, 0.0)));
  dir.write("walls/blocks/block.xml", testing::sceneXml(R"(
  <part name="FACE" file="../../meshes/cube.ply" attached_to="ROOT" offset="0 0 1 0 0 0"/>
)"));
  dir.write("walls/pylon.xml", testing::sceneXml(R"(
  <part name="BRIDGE" attached_to="ROOT" offset="0 10 0 0 0 0"/>
  <part name="BLOCK" file="blocks/block.xml" attached_to="BRIDGE" offset="1 0 0 0 0 0"/>
  <part name="PLATE" file="../meshes/cube.ply" attached_to="ROOT:BRIDGE:BLOCK:FACE"/>
)"));
  const auto top = dir.write("top.xml", testing::sceneXml(R"(
  <part name="WORLD" file="walls/pylon.xml" attached_to="ROOT" offset="100 0 0 0 0 0"/>
  <part name="OTHER" file="walls/pylon.xml" attached_to="ROOT" offset="200 0 0 0 0 0"/>
  <part name="ROBOT" attached_to="ROOT:WORLD:BRIDGE:BLOCK:FACE"/>
)"));
  const Scene scene = loadScene(top);
  EXPECT_EQ(scene.parts()[scene.partIndex("ROBOT")].full_name, "ROOT:WORLD:BRIDGE:BLOCK:FACE:ROBOT");
  EXPECT_LT((scene.worldPose("ROBOT").translation() - Eigen::Vector3d(101, 10, 1)).norm(), 1e-12);
  EXPECT_LT((scene.worldPose("ROOT:OTHER:BRIDGE:BLOCK:FACE:PLATE").translation() - Eigen::Vector3d(201, 10, 1)).norm(),
            1e-12);
  // One mesh file, read once, carried by four parts: 4 * 2 triangles.
  EXPECT_EQ(scene.description().meshes.size(), 1u);
  EXPECT_EQ(scene.staticMesh().triangles.size(), 8u);
  // Inside each copy of pylon.xml the short name FACE is unique; from the top it is not.
  EXPECT_THROW(scene.partIndex("FACE"), ConfigError);
}

TEST(SceneNames, ThePartsAPoseElementMovesAreItsSubtree) {
  testing::TempDir dir;
  const auto file = dir.write("s.xml", testing::sceneXml(R"(
  <part name="WALL" attached_to="ROOT"/>
  <part name="ROBOT" attached_to="WALL"/>
  <part name="STONE" attached_to="WALL"/>
  <part name="ARM" attached_to="ROBOT"/>
  <part name="TCP" attached_to="ARM"/>
  <part name="CHASSIS" attached_to="ROBOT"/>
  <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
)"));
  const Scene scene = loadScene(file);
  std::vector<std::string> moved;
  for (auto id : scene.partsMovedBy("robot_pose")) moved.push_back(scene.parts()[id].name);
  std::sort(moved.begin(), moved.end());
  EXPECT_EQ(moved, (std::vector<std::string>{"ARM", "CHASSIS", "ROBOT", "TCP"}));
}

}  // namespace
}  // namespace climbsim::scene
