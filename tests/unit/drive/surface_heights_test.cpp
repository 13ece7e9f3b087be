// The surface the drive's wheels stand on (climbsim/wall/surface_heights.hpp): heights of
// triangles on the grid, a sphere resting on a level patch, at a step's edge, over a groove and
// over a hole deeper than the reach; the surface enveloped over a tyre's contact patch.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

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

constexpr double kPatch = 0.02;  // 21 grid points: the shipped robot's tyre patch

TEST(SurfaceHeights, EnvelopedALevelWallKeepsItsHeightExactlyAcrossTiles) {
  TriangleMesh mesh;
  addRectangle(mesh, -1, 1, -1, 1, 0.003);
  const SurfaceHeights surface(std::move(mesh), 0.05, SurfaceHeights::kDefaultCell_m, kPatch);
  for (const double x : {0.0, 0.0635, 0.0645, -0.3337}) {
    const SphereRest rest = surface.sphereRest(x, 0.2718, kR);
    ASSERT_TRUE(rest.touches);
    EXPECT_TRUE(rest.level) << x;
    EXPECT_EQ(rest.centre_z_m, double(0.003f) + kR) << x;
  }
}

TEST(SurfaceHeights, EnvelopedAStepUnderTheWholePatchGivesItsFullHeightAndItsEdgeARamp) {
  TriangleMesh mesh;
  addRectangle(mesh, -1, 0, -1, 1, 0.008);
  addRectangle(mesh, 0.0005, 1, -1, 1, 0.0);
  const SurfaceHeights surface(std::move(mesh), 0.05, SurfaceHeights::kDefaultCell_m, kPatch);
  // The patch's 21 points about x = -11 mm and below all lie on the upper level, about +11 mm
  // and above on the lower; between them the height falls by 8 mm / 21 a grid step.
  EXPECT_EQ(surface.height(-11, 100), 0.008f);
  EXPECT_EQ(surface.height(-300, 100), 0.008f);
  EXPECT_EQ(surface.height(11, 100), 0.0f);
  EXPECT_NEAR(surface.height(0, 100), 0.008 * 11.0 / 21.0, 1e-7);
  EXPECT_NEAR(surface.height(-5, 100) - surface.height(-4, 100), 0.008 / 21.0, 1e-7);
  // A wheel far over the upper level stands 8 mm higher: the step lifts it in full.
  EXPECT_EQ(surface.sphereRest(-0.2, 0.1, kR).centre_z_m, double(0.008f) + kR);
}

TEST(SurfaceHeights, EnvelopedRidgesShorterThanThePatchCarryTheWheelAtTheirMeanHeight) {
  // Ridges 2 mm wide, 1 mm high, every 4 mm across x (two grid points of four on a ridge).
  auto ridges = [] {
    TriangleMesh mesh;
    addRectangle(mesh, -1, 1, -1, 1, 0.0);
    for (int k = -100; k < 100; ++k) addRectangle(mesh, 0.004 * k + 0.0005, 0.004 * k + 0.0025, -1, 1, 0.001);
    return mesh;
  };
  const SurfaceHeights sampled(ridges(), 0.05);
  const SurfaceHeights enveloped(ridges(), 0.05, SurfaceHeights::kDefaultCell_m, kPatch);
  for (const double x : {0.0, 0.0013, 0.1007}) {
    // On the sampled surface the wheel rides the ridges' tops; enveloped, their mean (10 or 11
    // of the 21 points are on a ridge: 0.476 to 0.524 mm) within the ridges' 1 mm.
    EXPECT_NEAR(sampled.sphereRest(x, 0.1, kR).centre_z_m - kR, 0.001, 2e-5) << x;
    EXPECT_NEAR(enveloped.sphereRest(x, 0.1, kR).centre_z_m - kR, 0.0005, 0.00003) << x;
  }
}

TEST(SurfaceHeights, EnvelopedAGapWiderThanPatchAndWheelAndDeeperThanTheReachGivesNoContact) {
  TriangleMesh mesh;
  // No surface from x = -100 to +100 mm (grid points).
  addRectangle(mesh, -1, -0.1005, -1, 1, 0.0);
  addRectangle(mesh, 0.1005, 1, -1, 1, 0.0);
  addRectangle(mesh, -0.1005, 0.1005, -1, 1, -0.08);  // deeper than the 50 mm reach
  const SurfaceHeights surface(std::move(mesh), 0.05, SurfaceHeights::kDefaultCell_m, kPatch);
  EXPECT_FALSE(surface.sphereRest(0.0, 0.0, kR).touches);
  // The rim's height reaches half a patch (10 points) into the gap.
  EXPECT_FALSE(std::isfinite(surface.height(-90, 0)));
  EXPECT_EQ(surface.height(-91, 0), 0.0);
  EXPECT_TRUE(surface.sphereRest(0.0, 0.0, 0.095).touches);
}

/// A rough wall: vertices every 2 mm over [-0.15, 0.15]² m at heights of a few sines up to
/// about ±1.5 mm, as triangles.
TriangleMesh roughWall() {
  TriangleMesh mesh;
  constexpr int kN = 151;
  for (int j = 0; j < kN; ++j) {
    for (int i = 0; i < kN; ++i) {
      const double x = -0.15 + 0.002 * i, y = -0.15 + 0.002 * j;
      const double z = 0.0007 * std::sin(173.0 * x + 2.0) * std::cos(131.0 * y) + 0.0005 * std::sin(911.0 * x * y + 37.0 * y) +
                       0.0003 * std::cos(2311.0 * x + 1777.0 * y);
      mesh.vertices_m.emplace_back(float(x), float(y), float(z));
    }
  }
  for (int j = 0; j + 1 < kN; ++j) {
    for (int i = 0; i + 1 < kN; ++i) {
      const auto v = static_cast<std::uint32_t>(j * kN + i);
      mesh.triangles.push_back({v, v + 1, v + kN + 1});
      mesh.triangles.push_back({v, v + kN + 1, v + kN});
      mesh.part_ids.insert(mesh.part_ids.end(), 2, 0);
    }
  }
  return mesh;
}

TEST(SurfaceHeights, OnARoughWallTheSearchFindsTheHighestRestOverEveryGridPoint) {
  // The search skips rows, runs and blocks of grid points whose highest point cannot beat the
  // best so far; it must still find the maximum of h + sqrt(r² - rho²) over every grid point
  // within r (the vertex of the parabolas through it and its neighbours may lift it, by less
  // than a grid step, never lower it).
  for (const double patch : {0.0, kPatch}) {
    const SurfaceHeights surface(roughWall(), 0.05, SurfaceHeights::kDefaultCell_m, patch);
    int grid_points_won = 0;
    for (int k = 0; k < 120; ++k) {
      const double x = -0.06 + 0.001037 * k, y = 0.05 * std::sin(0.37 * k);
      double best = -std::numeric_limits<double>::infinity();
      for (std::int64_t j = std::int64_t(std::ceil((y - kR) * 1000)); j <= std::int64_t(std::floor((y + kR) * 1000)); ++j) {
        for (std::int64_t i = std::int64_t(std::ceil((x - kR) * 1000)); i <= std::int64_t(std::floor((x + kR) * 1000)); ++i) {
          const double px = 0.001 * double(i) - x, py = 0.001 * double(j) - y;
          const double room = kR * kR - (px * px + py * py);
          if (room > 0.0) best = std::max(best, surface.height(i, j) + std::sqrt(room));
        }
      }
      const SphereRest rest = surface.sphereRest(x, y, kR);
      ASSERT_TRUE(rest.touches);
      EXPECT_GE(rest.centre_z_m, best - 1e-12) << "patch " << patch << ", x " << x << ", y " << y;
      EXPECT_LE(rest.centre_z_m, best + SurfaceHeights::kDefaultCell_m) << "patch " << patch << ", x " << x << ", y " << y;
      grid_points_won += rest.point_m.x() != x || rest.point_m.y() != y ? 1 : 0;  // not the point below the centre
    }
    EXPECT_GT(grid_points_won, 60) << "patch " << patch;  // the wall is rough enough to need the search
  }
}

}  // namespace
}  // namespace climbsim::scene
