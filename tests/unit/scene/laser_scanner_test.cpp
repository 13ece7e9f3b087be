// Laser scanner: ranges against analytic walls and a corner,
// out-of-range beams, excluded parts, beam layout.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "analytic_scenes.hpp"
#include "climbsim/errors.hpp"
#include "render_scene.hpp"

namespace climbsim::scene {
namespace {

using testing::pose;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A rectangle in the plane x = x0 of frame S: y in [y_lo, y_hi], z in [-1, 1], part `part`.
TriangleMesh wallAtX(double x0, double y_lo, double y_hi, std::uint32_t part) {
  TriangleMesh m;
  m.vertices_m = {{float(x0), float(y_lo), -1.f}, {float(x0), float(y_hi), -1.f}, {float(x0), float(y_hi), 1.f},
                  {float(x0), float(y_lo), 1.f}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.part_ids = {part, part};
  return m;
}

// A rectangle in the plane y = y0 of frame S: x in [x_lo, x_hi], z in [-1, 1].
TriangleMesh wallAtY(double y0, double x_lo, double x_hi, std::uint32_t part) {
  TriangleMesh m;
  m.vertices_m = {{float(x_lo), float(y0), -1.f}, {float(x_hi), float(y0), -1.f}, {float(x_hi), float(y0), 1.f},
                  {float(x_lo), float(y0), 1.f}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.part_ids = {part, part};
  return m;
}

// Scanner somewhere in the world, rolled and yawed: ranges do not depend on where S is.
const Pose kScannerInWorld = pose(1.3, -2.1, 0.7, 15.0, -10.0, 35.0);

// Distance along (cos a, sin a) from the origin to the line x = x0 within y in [y_lo, y_hi].
double rangeToX(double a, double x0, double y_lo, double y_hi) {
  const double c = std::cos(a);
  if (c * x0 <= 0.0) return kInf;
  const double t = x0 / c;
  const double y = t * std::sin(a);
  return (y >= y_lo && y <= y_hi) ? t : kInf;
}

double rangeToY(double a, double y0, double x_lo, double x_hi) {
  const double s = std::sin(a);
  if (s * y0 <= 0.0) return kInf;
  const double t = y0 / s;
  const double x = t * std::cos(a);
  return (x >= x_lo && x <= x_hi) ? t : kInf;
}

void expectRange(float measured, double expected, int beam, double range_max) {
  if (expected > range_max) expected = kInf;
  if (std::isinf(expected)) {
    EXPECT_TRUE(std::isinf(measured) && measured > 0) << "beam " << beam << " measured " << measured;
  } else {
    EXPECT_NEAR(measured, expected, 2e-6 * range_max + 1e-6) << "beam " << beam;
  }
}

TEST(LaserParams, DefaultsAre240DegreesIn682BeamsOver4m) {
  const LaserParams p;
  EXPECT_EQ(p.beam_count, 682);
  EXPECT_NEAR(p.beamAngle_rad(0), -120.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(p.beamAngle_rad(681), 120.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(p.angle_increment_rad * 180.0 / kPi, 0.352423, 1e-6);
  EXPECT_EQ(p.range_max_m, 4.0);
  const LaserParams xml = LaserParams::fromScanRange(240.0, 0.352423, 4.0);
  EXPECT_EQ(xml.beam_count, 682);
  EXPECT_NEAR(xml.angle_min_rad, p.angle_min_rad, 1e-12);
  EXPECT_EQ(LaserParams::fromScanRange(240.0, 0.352, 4.0).beam_count, 682);
  EXPECT_EQ(LaserParams::fromScanRange(180.0, 1.0, 4.0).beam_count, 181);
}

TEST(LaserParams, BadValuesAreRejectedNamingTheField) {
  try {
    LaserParams::fromScanRange(240.0, 0.01, 4.0);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("angular_resolution = 0.01"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LaserParams::fromScanRange(0.0, 1.0, 4.0), ConfigError);
  EXPECT_THROW(LaserParams::fromScanRange(240.0, 1.0, -1.0), ConfigError);
  LaserParams p;
  p.beam_count = 0;
  EXPECT_THROW(p.validate(), ConfigError);
}

TEST(LaserScanner, RangesToAPlaneWallAreDOverCosine) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, wallAtX(1.7, -50.0, 50.0, 0), kScannerInWorld);
  RenderScene scene(mesh);
  const LaserParams laser;
  const LaserScan scan = scene.scanLaser(kScannerInWorld, laser);
  ASSERT_EQ(scan.ranges_m.size(), 682u);
  int hits = 0, misses = 0;
  for (int i = 0; i < laser.beam_count; ++i) {
    const double expected = rangeToX(laser.beamAngle_rad(i), 1.7, -50.0, 50.0);
    expectRange(scan.ranges_m[i], expected, i, laser.range_max_m);
    (std::isinf(scan.ranges_m[i]) ? misses : hits)++;
  }
  // Within 4 m the wall covers |a| < acos(1.7 / 4) = 64.8 deg: 368 beams; behind it, nothing.
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 200);
}

TEST(LaserScanner, RangesIntoACornerTakeTheNearerWall) {
  // Corner at (1.2, 0.9): wall x = 1.2 for y <= 0.9, wall y = 0.9 for x <= 1.2; and behind
  // the scanner a wall x = -0.5 for y in [-3, 3], partly beyond the 4 m range.
  TriangleMesh mesh;
  testing::appendMesh(mesh, wallAtX(1.2, -20.0, 0.9, 0), kScannerInWorld);
  testing::appendMesh(mesh, wallAtY(0.9, -20.0, 1.2, 1), kScannerInWorld);
  RenderScene scene(mesh);
  LaserParams laser = LaserParams::fromScanRange(360.0, 0.5, 4.0);
  const LaserScan scan = scene.scanLaser(kScannerInWorld, laser);
  for (int i = 0; i < laser.beam_count; ++i) {
    const double a = laser.beamAngle_rad(i);
    expectRange(scan.ranges_m[i], std::min(rangeToX(a, 1.2, -20.0, 0.9), rangeToY(a, 0.9, -20.0, 1.2)), i,
                laser.range_max_m);
  }
}

TEST(LaserScanner, BeyondRangeMaxIsInfinityAndTheRangeIsReportedWithTheScan) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, wallAtX(1.7, -50.0, 50.0, 0), kScannerInWorld);
  RenderScene scene(mesh);
  LaserParams laser;
  laser.range_max_m = 1.5;
  const LaserScan scan = scene.scanLaser(kScannerInWorld, laser);
  for (const float r : scan.ranges_m) EXPECT_TRUE(std::isinf(r) && r > 0);
  EXPECT_EQ(scan.range_max_m, 1.5);
  EXPECT_TRUE(scan.T_W_S.isApprox(kScannerInWorld));
  laser.range_max_m = 1.7001;
  const LaserScan just = scene.scanLaser(kScannerInWorld, laser);
  const int ahead = 340;  // beam nearest to a = 0
  EXPECT_NEAR(laser.beamAngle_rad(ahead), -0.5 * laser.angle_increment_rad, 1e-12);
  expectRange(just.ranges_m[ahead], rangeToX(laser.beamAngle_rad(ahead), 1.7, -50, 50), ahead, laser.range_max_m);
}

TEST(LaserScanner, HitsNearerThanRangeMinAreIgnored) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, wallAtX(0.5, -0.3, 0.3, 0), kScannerInWorld);
  testing::appendMesh(mesh, wallAtX(2.0, -50.0, 50.0, 1), kScannerInWorld);
  RenderScene scene(mesh);
  LaserParams laser;
  laser.range_min_m = 1.0;
  const LaserScan scan = scene.scanLaser(kScannerInWorld, laser);
  for (int i = 0; i < laser.beam_count; ++i) {
    expectRange(scan.ranges_m[i], rangeToX(laser.beamAngle_rad(i), 2.0, -50, 50), i, laser.range_max_m);
  }
}

TEST(LaserScanner, ExcludedPartsAndMovingBodies) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, wallAtX(2.0, -50.0, 50.0, 0), kScannerInWorld);
  testing::appendMesh(mesh, wallAtX(1.0, -0.2, 0.2, 3), kScannerInWorld);  // a static obstacle, part 3
  RenderScene scene(mesh);
  const LaserParams laser;
  const LaserScan without = scene.scanLaser(kScannerInWorld, laser, {3});
  const LaserScan with = scene.scanLaser(kScannerInWorld, laser, {});
  for (int i = 0; i < laser.beam_count; ++i) {
    const double a = laser.beamAngle_rad(i);
    expectRange(without.ranges_m[i], rangeToX(a, 2.0, -50, 50), i, laser.range_max_m);
    expectRange(with.ranges_m[i], std::min(rangeToX(a, 2.0, -50, 50), rangeToX(a, 1.0, -0.2, 0.2)), i,
                laser.range_max_m);
  }
  // A moving body (a plate in its own frame, part 9) placed 0.6 m ahead, then moved to 1.4 m.
  const auto body = scene.addBody(wallAtX(0.0, -0.1, 0.1, 9), kScannerInWorld * pose(0.6, 0, 0, 0, 0, 0));
  const int ahead = 340;
  EXPECT_NEAR(scene.scanLaser(kScannerInWorld, laser, {3}).ranges_m[ahead], 0.6 / std::cos(laser.beamAngle_rad(ahead)),
              1e-5);
  EXPECT_NEAR(scene.scanLaser(kScannerInWorld, laser, {3, 9}).ranges_m[ahead], 2.0 / std::cos(laser.beamAngle_rad(ahead)),
              1e-5);
  scene.setBodyPose(body, kScannerInWorld * pose(1.4, 0, 0, 0, 0, 0));
  EXPECT_NEAR(scene.scanLaser(kScannerInWorld, laser, {3}).ranges_m[ahead], 1.4 / std::cos(laser.beamAngle_rad(ahead)),
              1e-5);
}

TEST(LaserScanner, ARendererBuiltWithoutEmbreeRendersTheSameDepthAndRefusesScans) {
  TriangleMesh mesh = testing::meshWall(testing::refined(testing::step(), 0.01, 0.3));
  testing::appendMesh(mesh, wallAtX(2.0, -50.0, 50.0, 0), kScannerInWorld);
  RenderOptions without_embree;
  without_embree.embree = false;
  RenderScene with(mesh);
  RenderScene without(mesh, without_embree);
  const TriangleMesh plate = wallAtX(0.0, -0.1, 0.1, 9);
  const Pose plate_pose = pose(0.05, 0.02, 0.01, 0, -90, 0);
  with.addBody(plate, plate_pose);
  without.addBody(plate, plate_pose);
  const Pose camera_pose = pose(0.01, -0.02, 0.02, 2.0, -1.0, 20.0);
  const DepthImage a = with.renderDepth(camera_pose);
  const DepthImage b = without.renderDepth(camera_pose);
  ASSERT_EQ(a.height_m.size(), b.height_m.size());
  std::size_t not_far = 0;
  for (std::size_t i = 0; i < a.height_m.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a.height_m[i], &b.height_m[i], sizeof(float)), 0) << "pixel " << i;
    not_far += a.height_m[i] > -0.05f ? 1 : 0;
  }
  EXPECT_GT(not_far, a.height_m.size() / 2);  // the step is seen, not an empty image twice
  EXPECT_THROW(without.scanLaser(kScannerInWorld), std::logic_error);
  DepthImage by_embree;
  EXPECT_THROW(without.renderDepth(camera_pose, DepthCameraParams{}, {}, DepthBackend::kEmbree, by_embree),
               std::logic_error);
  RenderOptions embree_backend = without_embree;
  embree_backend.depth_backend = DepthBackend::kEmbree;
  EXPECT_THROW(RenderScene(mesh, embree_backend), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::scene
