// The drive names each wheel once, at the first step its contact point has no wall under it,
// at the pose the model reached (position and orientation).

#include <gtest/gtest.h>

#include <cmath>

#include "wheels_over_scene.hpp"

namespace climbsim::drive {
namespace {

/// A wall [0, 2] x [0, 2] m at z = 0 of the wall frame.
scene::WallCoverage wall2x2() {
  scene::TriangleMesh mesh;
  mesh.vertices_m = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.part_ids = {0, 0};
  return scene::WallCoverage(mesh, 0.05);
}

DriveOutputs at(double x, double y, double yaw_rad) {
  DriveOutputs o;
  o.position_m = {x, y, 0.0};
  o.orientation_wxyz = {std::cos(yaw_rad / 2), 0.0, 0.0, std::sin(yaw_rad / 2)};
  return o;
}

TEST(WheelsOverScene, EachWheelIsNamedOnceWhenItsContactPointLeavesTheWall) {
  // Three wheels 0.26 m from the centre, at 0, 120 and 240 degrees.
  std::vector<WheelMount> wheels;
  for (int i = 0; i < 3; ++i) wheels.push_back({0.26 * std::cos(i * 2 * M_PI / 3), 0.26 * std::sin(i * 2 * M_PI / 3)});
  WheelsOverScene check(wall2x2(), wheels);
  EXPECT_TRUE(check.newlyOverNothing(at(1.0, 1.0, 0.0)).empty());
  // 1.8 + 0.26 = 2.06: wheel 1 (along R's x) is past the right edge, the others are not.
  EXPECT_EQ(check.newlyOverNothing(at(1.8, 1.0, 0.0)), std::vector<std::size_t>{0});
  EXPECT_TRUE(check.newlyOverNothing(at(1.8, 1.0, 0.0)).empty()) << "named once";
  // Turned by 180 degrees at the left edge: wheel 1 points left (x = 0.2 - 0.26 < 0).
  WheelsOverScene turned(wall2x2(), wheels);
  const auto p = turned.contactPoint(at(0.2, 1.0, M_PI), 0);
  EXPECT_NEAR(p[0], 0.2 - 0.26, 1e-12);
  EXPECT_NEAR(p[1], 1.0, 1e-12);
  EXPECT_EQ(turned.newlyOverNothing(at(0.2, 1.0, M_PI)), std::vector<std::size_t>{0});
  // Far off the wall: every wheel not named yet.
  EXPECT_EQ(turned.newlyOverNothing(at(5.0, 5.0, 0.0)), (std::vector<std::size_t>{1, 2}));
}

}  // namespace
}  // namespace climbsim::drive
