// Where a scene has a wall under a point of the wall plane (wall_coverage.hpp): edges found to
// within half a cell, surfaces deeper than the reach count as nothing, and the wall frame is
// the parent of the robot's pose part, whatever its pose in the scene.

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "climbsim/wall/scene.hpp"
#include "scene_test_files.hpp"
#include "climbsim/wall/scene_xml.hpp"
#include "climbsim/wall/wall_coverage.hpp"
#include "rectangle_mesh.hpp"

namespace climbsim::scene {
namespace {

using testing::TempDir;

TEST(WallCoverage, AWallIsCoveredToWithinHalfACellOfItsEdgesAndNothingBeyond) {
  TriangleMesh mesh;
  addRectangle(mesh, -1.0, 2.0, -0.5, 0.5, 0.0);
  const WallCoverage coverage(mesh, 0.05, 0.005);
  EXPECT_TRUE(coverage.covered(0.0, 0.0));
  EXPECT_TRUE(coverage.covered(-0.99, 0.49));
  EXPECT_TRUE(coverage.covered(1.99, -0.49));
  EXPECT_FALSE(coverage.covered(2.01, 0.0)) << "past the right edge";
  EXPECT_FALSE(coverage.covered(0.0, 0.51)) << "above the top edge";
  EXPECT_FALSE(coverage.covered(-5.0, 0.0));
  EXPECT_FALSE(coverage.covered(std::nan(""), 0.0));
  EXPECT_NEAR(coverage.minX(), -1.0, 0.005);
  EXPECT_NEAR(coverage.maxX(), 2.0, 0.005);
  EXPECT_NEAR(coverage.minY(), -0.5, 0.005);
  EXPECT_NEAR(coverage.maxY(), 0.5, 0.005);
}

TEST(WallCoverage, ASurfaceDeeperThanTheReachIsNothingAndOneAboveThePlaneIsWall) {
  TriangleMesh mesh;
  addRectangle(mesh, 0.0, 1.0, 0.0, 1.0, 0.0);
  addRectangle(mesh, 1.0, 2.0, 0.0, 1.0, -0.2);  // a pit floor 20 cm below the plane
  addRectangle(mesh, 2.0, 3.0, 0.0, 1.0, 0.3);   // a step 30 cm up
  addRectangle(mesh, 3.0, 4.0, 0.0, 1.0, -0.04); // a shallow groove, within reach
  const WallCoverage coverage(mesh, 0.05);
  EXPECT_TRUE(coverage.covered(0.5, 0.5));
  EXPECT_FALSE(coverage.covered(1.5, 0.5)) << "deeper than the reach";
  EXPECT_TRUE(coverage.covered(2.5, 0.5));
  EXPECT_TRUE(coverage.covered(3.5, 0.5));
  const WallCoverage deep(mesh, 0.5);
  EXPECT_TRUE(deep.covered(1.5, 0.5)) << "within a reach of 0.5 m";
}

TEST(WallCoverage, ManySmallTrianglesLeaveNoGapAndAnEmptySceneCoversNothing) {
  TriangleMesh mesh;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 50; ++j) addRectangle(mesh, i * 0.0013, (i + 1) * 0.0013, j * 0.0021, (j + 1) * 0.0021, 0.0);
  }
  const WallCoverage coverage(mesh, 0.05);
  for (double x = 0.003; x < 0.127; x += 0.0031) {
    for (double y = 0.003; y < 0.102; y += 0.0047) EXPECT_TRUE(coverage.covered(x, y)) << x << " " << y;
  }
  const WallCoverage none(TriangleMesh{}, 0.05);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.covered(0.0, 0.0));
}

TEST(WallCoverage, TheWallFrameIsTheParentOfTheRobotsPosePartAndTheRobotIsNotWall) {
  TempDir dir;
  dir.write("wall.obj", testing::asObj(testing::square(2.0, 0.0)));  // x, y in -1..1 of its part
  dir.write("robot.obj", testing::asObj(testing::square(0.5, 0.0)));
  // WALL stands up (rotated 90 deg about ROOT's x, 6 m up); the wall mesh sits 3 m along W's x.
  const std::string file = dir.write("scene.xml", testing::sceneXml(R"(
  <part name="WALL" file="" attached_to="ROOT" offset="0 0 6 90 0 0"/>
  <part name="BLOCK" file="wall.obj" attached_to="WALL" offset="3 0 0 0 0 0"/>
  <part name="ROBOT" file="robot.obj" attached_to="WALL" offset="10 10 0 0 0 0"/>
  <element name="robot_pose" type="3d Pose" angle_type="rad" attached_to="ROBOT"/>
  <camera name="depth_cam" type="orthographic" near_limit="-0.05" far_limit="0.07" attached_to="ROBOT"/>
)"));
  const SceneDescription description = loadSceneDescription(file);
  EXPECT_DOUBLE_EQ(coverageReach(description), 0.07);
  const Scene scene(description);
  const WallCoverage coverage = wallCoverage(scene, "robot_pose", coverageReach(description));
  EXPECT_TRUE(coverage.covered(3.0, 0.0));
  EXPECT_TRUE(coverage.covered(2.05, 0.95));
  EXPECT_FALSE(coverage.covered(1.9, 0.0));
  EXPECT_FALSE(coverage.covered(10.0, 10.0)) << "the robot's own mesh is no wall";
  EXPECT_NEAR(coverage.minX(), 2.0, 0.005);
  EXPECT_NEAR(coverage.maxY(), 1.0, 0.005);
  EXPECT_THROW(wallCoverage(scene, "no_such_element", 0.05), ConfigError);
}

}  // namespace
}  // namespace climbsim::scene
