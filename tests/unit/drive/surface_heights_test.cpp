// The surface the drive's wheels stand on (climbsim/wall/surface_heights.hpp): heights of
// triangles on the grid, a sphere resting on a level patch, at a step's edge, over a groove and
// over a hole deeper than the reach.

#include <gtest/gtest.h>

#include <cmath>

#include "climbsim/wall/surface_heights.hpp"
#include "rectangle_mesh.hpp"

namespace climbsim::scene {
namespace {

constexpr double kR = 0.05;

TEST(SurfaceHeights, ASphereOnALevelWallRestsAtItsRadiusExactly) {
  TriangleMesh mesh;
  addRectangle(mesh, -1, 1, -1, 1, 0.0);
  const SurfaceHeights surface(std::move(mesh), 0.05);
  for (const double x : {0.0, 0.01234, -0.3337, 0.5}) {
    const SphereRest rest = surface.sphereRest(x, 0.2718, kR);
    ASSERT_TRUE(rest.touches);
    EXPECT_TRUE(rest.level);
    EXPECT_EQ(rest.centre_z_m, kR);
    EXPECT_EQ(rest.point_m.z(), 0.0);
    EXPECT_EQ(rest.normal, Eigen::Vector3d::UnitZ());
  }
}

TEST(SurfaceHeights, AtAStepsEdgeTheSphereRestsOnTheEdgeWithATiltedNormal) {
  // Upper level x < 0 at 8 mm, lower level x > 0 at 0: a sphere over the lower level 20 mm
  // from the edge touches the edge, centre height 8 mm + sqrt(r² - 20²), normal from the edge.
  TriangleMesh mesh;
  addRectangle(mesh, -1, 0, -1, 1, 0.008);
  addRectangle(mesh, 0, 1, -1, 1, 0.0);
  const SurfaceHeights surface(std::move(mesh), 0.05);
  const SphereRest rest = surface.sphereRest(0.0203, 0.1, kR);
  ASSERT_TRUE(rest.touches);
  EXPECT_FALSE(rest.level);
  EXPECT_NEAR(rest.centre_z_m, 0.008 + std::sqrt(kR * kR - 0.0203 * 0.0203), 1e-6);
  EXPECT_NEAR(rest.point_m.x(), 0.0, 1e-9);
  EXPECT_NEAR(rest.normal.x(), 0.0203 / kR, 1e-3);
  // Far from the edge the sphere stands level on the lower level.
  const SphereRest away = surface.sphereRest(0.0603, 0.1, kR);
  EXPECT_TRUE(away.level);
  EXPECT_EQ(away.centre_z_m, kR);
}

TEST(SurfaceHeights, OverAGrooveNarrowerThanTheSphereItRestsOnBothEdges) {
  // A groove 20 mm wide, 40 mm deep along y: the sphere centred over it rests on its edges at
  // sqrt(r² - 10²) above the wall.
  TriangleMesh mesh;
  addRectangle(mesh, -1, -0.01, -1, 1, 0.0);
  addRectangle(mesh, 0.01, 1, -1, 1, 0.0);
  addRectangle(mesh, -0.01, 0.01, -1, 1, -0.04);
  const SurfaceHeights surface(std::move(mesh), 0.05);
  const SphereRest rest = surface.sphereRest(0.0, 0.3, kR);
  ASSERT_TRUE(rest.touches);
  EXPECT_NEAR(rest.centre_z_m, std::sqrt(kR * kR - 0.01 * 0.01), 1e-9);
  EXPECT_NEAR(std::fabs(rest.point_m.x()), 0.01, 1e-9);
}

TEST(SurfaceHeights, BeyondTheReachThereIsNoSurface) {
  TriangleMesh mesh;
  addRectangle(mesh, -1, 1, -1, 1, -0.08);  // deeper than the 50 mm reach
  addRectangle(mesh, 0.5, 1, -1, 1, 0.0);
  const SurfaceHeights surface(std::move(mesh), 0.05);
  EXPECT_FALSE(std::isfinite(surface.height(0, 0)));
  EXPECT_EQ(surface.height(600, 0), 0.0);
  EXPECT_FALSE(surface.sphereRest(0.0, 0.0, kR).touches);
  EXPECT_TRUE(surface.sphereRest(0.46, 0.0, kR).touches);
}

}  // namespace
}  // namespace climbsim::scene
