// Depth camera: both backends against analytic walls, robot parts
// switched off, clipping at near, far for empty pixels, 8-bit quantisation.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "analytic_scenes.hpp"
#include "climbsim/errors.hpp"
#include "depth_rasterizer.hpp"
#include "render_scene.hpp"
#include "triangle_index.hpp"

namespace climbsim::scene {
namespace {

using testing::AnalyticWall;
using testing::pose;

constexpr double kTolerance_m = 1e-4;  // the camera's promise: within 0.1 mm

// A pylon face: the wall frame F stands vertical in the world, its z (out of the wall) along
// world -y, away from the origin.
Pose wallInWorld() { return pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0) * pose(0, 0, 0, 0, 0, 180.0); }

struct Case {
  DepthBackend backend;
  std::string name;
};

class DepthBackends : public ::testing::TestWithParam<DepthBackend> {
 protected:
  // Renders `wall` placed at wallInWorld() with the camera at T_F_C in the wall frame and
  // returns the largest |depth - analytic| over all pixels.
  double maxError(const AnalyticWall& wall, const Pose& T_F_C, const DepthCameraParams& camera = {}) {
    TriangleMesh mesh;
    testing::appendMesh(mesh, testing::meshWall(wall), wallInWorld());
    RenderScene scene(mesh);
    const DepthImage image = render(scene, wallInWorld() * T_F_C, camera, {});
    EXPECT_EQ(image.width_px, camera.width_px);
    EXPECT_EQ(image.height_px, camera.height_px);
    double worst = 0.0;
    for (int r = 0; r < camera.height_px; ++r) {
      for (int c = 0; c < camera.width_px; ++c) {
        const double expected = testing::expectedDepth(wall, T_F_C, camera, r, c);
        worst = std::max(worst, std::abs(image.at(r, c) - expected));
      }
    }
    return worst;
  }

  DepthImage render(RenderScene& scene, const Pose& T_W_C, const DepthCameraParams& camera,
                    const std::vector<std::uint32_t>& excluded) {
    DepthImage image;
    scene.renderDepth(T_W_C, camera, excluded, GetParam(), image);
    return image;
  }
};

const Pose kAligned = pose(0.013, -0.021, 0.0, 0, 0, 0);
const Pose kYawed = pose(0.013, -0.021, 0.0, 0, 0, 30.0);
const Pose kTilted = pose(0.017, 0.009, 0.004, 6.0, -4.0, 20.0);

TEST_P(DepthBackends, TiltedPlaneMatchesAnalyticForAlignedYawedAndTiltedCameras) {
  EXPECT_LT(maxError(testing::tiltedPlane(), kAligned), kTolerance_m);
  EXPECT_LT(maxError(testing::tiltedPlane(), kYawed), kTolerance_m);
  EXPECT_LT(maxError(testing::tiltedPlane(), kTilted), kTolerance_m);
}

TEST_P(DepthBackends, StepMatchesAnalytic) {
  EXPECT_LT(maxError(testing::step(), kAligned), kTolerance_m);
  EXPECT_LT(maxError(testing::step(), kYawed), kTolerance_m);
  EXPECT_LT(maxError(testing::step(), kTilted), kTolerance_m);
}

TEST_P(DepthBackends, RectangularHolesMatchAnalyticTheDeepOneClampedToFar) {
  EXPECT_LT(maxError(testing::rectangularHole(), kAligned), kTolerance_m);
  EXPECT_LT(maxError(testing::rectangularHole(), kYawed), kTolerance_m);
  EXPECT_LT(maxError(testing::rectangularHole(), kTilted), kTolerance_m);
}

TEST_P(DepthBackends, VGrooveMatchesAnalytic) {
  EXPECT_LT(maxError(testing::vGroove(), kAligned), kTolerance_m);
  EXPECT_LT(maxError(testing::vGroove(), kYawed), kTolerance_m);
  EXPECT_LT(maxError(testing::vGroove(), kTilted), kTolerance_m);
}

TEST_P(DepthBackends, OddImageSizesAndFinePixelsMatchAnalytic) {
  DepthCameraParams camera;
  camera.width_px = 61;
  camera.height_px = 37;
  camera.pixel_size_m = 0.0021;
  EXPECT_LT(maxError(testing::vGroove(), kYawed, camera), kTolerance_m);
  EXPECT_LT(maxError(testing::rectangularHole(), kTilted, camera), kTolerance_m);
}

TEST_P(DepthBackends, FineMeshesWithPixelSizedTrianglesMatchAnalytic) {
  // 3.7 mm cells against 3.125 mm pixels: most triangles cover one pixel centre or none.
  EXPECT_LT(maxError(testing::refined(testing::vGroove(), 0.0037, 0.6), kYawed), kTolerance_m);
  EXPECT_LT(maxError(testing::refined(testing::rectangularHole(), 0.0037, 0.6), kTilted), kTolerance_m);
  EXPECT_LT(maxError(testing::refined(testing::tiltedPlane(), 0.0021, 0.6), kAligned), kTolerance_m);
}

TEST_P(DepthBackends, SealingPlaneAboveTheWallShiftsEveryHeight) {
  // The robot 4 mm off the wall: every height drops by 4 mm (the oracle knows nothing of meshes).
  EXPECT_LT(maxError(testing::step(), pose(0.013, -0.021, 0.004, 0, 0, 30.0)), kTolerance_m);
}

// The wall plus a 6 cm box part (id 7) floating 1..3 cm above it inside the window.
TriangleMesh wallWithBox(std::uint32_t box_part) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, testing::meshWall(testing::tiltedPlane(), 0), wallInWorld());
  testing::appendMesh(mesh, testing::box({-0.05, -0.03, 0.02}, {0.01, 0.03, 0.04}, box_part), wallInWorld());
  return mesh;
}

double maxDifference(const DepthImage& a, const DepthImage& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.height_m.size(); ++i) worst = std::max(worst, std::abs(double{a.height_m[i]} - b.height_m[i]));
  return worst;
}

TEST_P(DepthBackends, ExcludedStaticPartNeverAppears) {
  TriangleMesh wall_only;
  testing::appendMesh(wall_only, testing::meshWall(testing::tiltedPlane(), 0), wallInWorld());
  RenderScene bare(wall_only);
  RenderScene with_box(wallWithBox(7));
  const DepthCameraParams camera;
  const Pose T_W_C = wallInWorld() * kYawed;
  const DepthImage reference = render(bare, T_W_C, camera, {});
  const DepthImage excluded = render(with_box, T_W_C, camera, {7, 12345});
  const DepthImage seen = render(with_box, T_W_C, camera, {});
  EXPECT_LT(maxDifference(excluded, reference), 1e-6);
  // Not excluded, the box's top (z_F = 0.04) fills its footprint: the test can fail.
  const Eigen::Vector3d top_C = kYawed.inverse() * Eigen::Vector3d(-0.02, 0.0, 0.04);
  const int col = static_cast<int>(std::floor(top_C.x() / camera.pixel_size_m + camera.width_px / 2.0));
  const int row = static_cast<int>(std::floor(camera.height_px / 2.0 - top_C.y() / camera.pixel_size_m));
  EXPECT_NEAR(seen.at(row, col), top_C.z(), kTolerance_m);
  EXPECT_LT(reference.at(row, col), 0.02);
}

TEST_P(DepthBackends, MovingBodyPartsAreExcludedPerPartAndFollowTheirPose) {
  TriangleMesh wall;
  testing::appendMesh(wall, testing::meshWall(testing::tiltedPlane(), 0), wallInWorld());
  RenderScene scene(wall);
  const DepthCameraParams camera;
  const Pose T_W_C = wallInWorld() * kTilted;
  const DepthImage reference = render(scene, T_W_C, camera, {});

  // The robot body B = camera frame C: a chassis box (part 20) and a wheel box (part 21).
  TriangleMesh robot = testing::box({-0.10, -0.10, 0.02}, {-0.05, 0.10, 0.03}, 20);
  testing::appendMesh(robot, testing::box({0.05, -0.02, 0.005}, {0.08, 0.02, 0.045}, 21));
  const auto body = scene.addBody(robot, T_W_C);
  EXPECT_LT(maxDifference(render(scene, T_W_C, camera, {20, 21}), reference), 1e-6);

  auto at = [&](const DepthImage& image, double x_C, double y_C) {
    const int col = static_cast<int>(std::floor(x_C / camera.pixel_size_m + camera.width_px / 2.0));
    const int row = static_cast<int>(std::floor(camera.height_px / 2.0 - y_C / camera.pixel_size_m));
    return double{image.at(row, col)};
  };
  const DepthImage wheel_only = render(scene, T_W_C, camera, {20});
  EXPECT_NEAR(at(wheel_only, 0.065, 0.0), 0.045, kTolerance_m);
  EXPECT_NEAR(at(wheel_only, -0.075, 0.0), at(reference, -0.075, 0.0), 1e-6);
  const DepthImage both = render(scene, T_W_C, camera, {});
  EXPECT_NEAR(at(both, -0.075, 0.0), 0.03, kTolerance_m);

  // The body moves 0.2 m along x_C: the chassis follows it.
  scene.setBodyPose(body, T_W_C * pose(0.2, 0.0, 0.0, 0, 0, 0));
  const DepthImage moved = render(scene, T_W_C, camera, {21});
  EXPECT_NEAR(at(moved, 0.125, 0.0), 0.03, kTolerance_m);
  EXPECT_NEAR(at(moved, -0.075, 0.0), at(reference, -0.075, 0.0), 1e-6);
}

TEST_P(DepthBackends, PixelsWithoutGeometryHoldFar) {
  // A 0.2 m square of wall in the middle of the 0.8 m window.
  AnalyticWall patch = testing::tiltedPlane();
  patch.x_lines = {-0.1, 0.0, 0.1};
  patch.y_lines = {-0.1, 0.0, 0.1};
  TriangleMesh mesh;
  testing::appendMesh(mesh, testing::meshWall(patch), wallInWorld());
  RenderScene scene(mesh);
  const DepthCameraParams camera;
  const DepthImage image = render(scene, wallInWorld() * kAligned, camera, {});
  int empty = 0, seen = 0;
  for (int r = 0; r < camera.height_px; ++r) {
    for (int c = 0; c < camera.width_px; ++c) {
      const double expected = testing::expectedDepth(patch, kAligned, camera, r, c);
      EXPECT_NEAR(image.at(r, c), expected, kTolerance_m);
      if (expected == camera.far_m) {
        EXPECT_EQ(image.at(r, c), static_cast<float>(camera.far_m));
        ++empty;
      } else {
        ++seen;
      }
    }
  }
  EXPECT_GT(empty, 50000);
  EXPECT_GT(seen, 3000);
}

TEST_P(DepthBackends, GeometryAboveNearIsClippedAndACutSolidShowsItsUnderside) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, testing::meshWall(testing::tiltedPlane(), 0), wallInWorld());
  // Entirely above near (0.05): not seen.
  testing::appendMesh(mesh, testing::box({-0.2, -0.2, 0.06}, {-0.1, -0.1, 0.09}, 1), wallInWorld());
  // Through near: the ray starts inside it and meets its underside at 0.03.
  testing::appendMesh(mesh, testing::box({0.1, 0.1, 0.03}, {0.2, 0.2, 0.07}, 2), wallInWorld());
  RenderScene scene(mesh);
  const DepthCameraParams camera;
  const DepthImage image = render(scene, wallInWorld() * kAligned, camera, {});
  int underside = 0;
  for (int r = 0; r < camera.height_px; ++r) {
    for (int c = 0; c < camera.width_px; ++c) {
      const Eigen::Vector3d p_F = kAligned * Eigen::Vector3d(camera.pixelCentreX_m(c), camera.pixelCentreY_m(r), 0.0);
      const bool under_cut_box = p_F.x() > 0.1 && p_F.x() < 0.2 && p_F.y() > 0.1 && p_F.y() < 0.2;
      if (under_cut_box) {
        EXPECT_NEAR(image.at(r, c), 0.03, kTolerance_m);
        ++underside;
      } else {
        EXPECT_NEAR(image.at(r, c), testing::expectedDepth(testing::tiltedPlane(), kAligned, camera, r, c), kTolerance_m);
      }
    }
  }
  EXPECT_GT(underside, 500);
}

TEST_P(DepthBackends, EightBitModeQuantisesAsSpecified) {
  TriangleMesh mesh;
  testing::appendMesh(mesh, testing::meshWall(testing::vGroove(), 0), wallInWorld());
  RenderScene scene(mesh);
  DepthCameraParams camera;
  const DepthImage exact = render(scene, wallInWorld() * kYawed, camera, {});
  camera.quantised_8bit = true;
  const DepthImage q = render(scene, wallInWorld() * kYawed, camera, {});
  EXPECT_TRUE(q.quantised_8bit);
  const double step = (camera.near_m - camera.far_m) / 256.0;
  std::vector<int> used(256, 0);
  for (std::size_t i = 0; i < q.height_m.size(); ++i) {
    const double level = (q.height_m[i] - camera.far_m) / step;
    const double k = std::round(level);
    ASSERT_NEAR(level, k, 1e-3) << "pixel " << i << " is not on a level";
    ASSERT_GE(k, 0.0);
    ASSERT_LE(k, 255.0);
    // Truncation towards far: the level lies in (h - step, h].
    EXPECT_LE(q.height_m[i], exact.height_m[i] + 1e-7);
    EXPECT_GT(q.height_m[i], exact.height_m[i] - step - 1e-7);
    used[static_cast<int>(k)] = 1;
  }
  // The groove spans 18.9 mm: about 48 levels.
  int levels = 0;
  for (const int u : used) levels += u;
  EXPECT_GT(levels, 40);
}

TEST_P(DepthBackends, EightBitLevelsOfFlatWalls) {
  const DepthCameraParams defaults;
  const double step = (defaults.near_m - defaults.far_m) / 256.0;
  for (const int k : {0, 1, 127, 128, 200, 254}) {
    AnalyticWall flat;
    const double h = defaults.far_m + (k + 0.3) * step;
    flat.height_m = [h](double, double) { return h; };
    flat.x_lines = {-1.0, 1.0};
    flat.y_lines = {-1.0, 1.0};
    TriangleMesh mesh;
    testing::appendMesh(mesh, testing::meshWall(flat), wallInWorld());
    RenderScene scene(mesh);
    DepthCameraParams camera;
    camera.quantised_8bit = true;
    const DepthImage q = render(scene, wallInWorld() * kAligned, camera, {});
    for (const float v : q.height_m) ASSERT_NEAR(v, quantisedHeight(k, camera.near_m, camera.far_m), 1e-7) << "k=" << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Both, DepthBackends, ::testing::Values(DepthBackend::kRasterizer, DepthBackend::kEmbree),
                         [](const ::testing::TestParamInfo<DepthBackend>& info) {
                           return std::string(toString(info.param));
                         });

TEST(DepthQuantisation, LevelsAreFloorBasedFromFar) {
  const double near = 0.05, far = -0.05, step = 0.1 / 256.0;
  EXPECT_EQ(quantisationLevel(far, near, far), 0);
  EXPECT_EQ(quantisedHeight(0, near, far), far);
  EXPECT_EQ(quantisationLevel(0.0, near, far), 128);
  EXPECT_NEAR(quantisedHeight(128, near, far), 0.0, 1e-15);
  EXPECT_EQ(quantisationLevel(near, near, far), 255);
  EXPECT_NEAR(quantisedHeight(255, near, far), near - step, 1e-15);
  EXPECT_EQ(quantisationLevel(far + 3.999 * step, near, far), 3);
  EXPECT_EQ(quantisationLevel(far - 1.0, near, far), 0);
  EXPECT_EQ(quantisationLevel(near + 1.0, near, far), 255);
}

TEST(DepthCameraParams, BadValuesAreRejectedNamingTheField) {
  auto message = [](const DepthCameraParams& p) {
    try {
      p.validate();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  DepthCameraParams p;
  EXPECT_EQ(message(p), "");
  p.width_px = 0;
  EXPECT_NE(message(p).find("width_px = 0"), std::string::npos);
  p = {};
  p.height_px = kMaxDepthImageSidePx + 1;
  EXPECT_NE(message(p).find("height_px = " + std::to_string(kMaxDepthImageSidePx + 1)), std::string::npos);
  p.height_px = kMaxDepthImageSidePx;
  EXPECT_EQ(message(p), "") << "the largest side is allowed";
  p = {};
  p.pixel_size_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(p).find("pixel_size_m"), std::string::npos);
  p = {};
  p.near_m = -0.06;
  EXPECT_NE(message(p).find("near_m = -0.06"), std::string::npos);
}

TEST(RenderScene, BadMeshesAndPosesAreRejected) {
  TriangleMesh mesh = testing::box({0, 0, 0}, {1, 1, 1}, 0);
  mesh.triangles[5][1] = 99;
  try {
    RenderScene scene(mesh);
    FAIL() << "accepted a triangle with a vertex index out of range";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 5 refers to vertex 99"), std::string::npos) << e.what();
  }
  mesh = testing::box({0, 0, 0}, {1, 1, 1}, 0);
  mesh.part_ids.pop_back();
  EXPECT_THROW(RenderScene{mesh}, ConfigError);
  mesh = testing::box({0, 0, 0}, {1, 1, 1}, 0);
  mesh.vertices_m[3].x() = std::numeric_limits<float>::infinity();
  EXPECT_THROW(RenderScene{mesh}, ConfigError);

  RenderScene scene(testing::box({0, 0, 0}, {1, 1, 1}, 0));
  Pose nan_pose = Pose::Identity();
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(scene.renderDepth(nan_pose), std::invalid_argument);
  EXPECT_THROW(scene.scanLaser(nan_pose), std::invalid_argument);
  EXPECT_THROW(scene.setBodyPose(3, Pose::Identity()), std::out_of_range);
}

TEST(RenderScene, EmptySceneGivesFarEverywhere) {
  RenderScene scene(TriangleMesh{});
  const DepthImage image = scene.renderDepth(Pose::Identity());
  for (const float v : image.height_m) ASSERT_EQ(v, -0.05f);
}

}  // namespace
}  // namespace climbsim::scene

namespace climbsim::scene {
namespace {

// Every kernel variant this CPU runs gives the same image bit for bit, and the analytic one.
TEST(RasterKernels, AllVariantsAgreeBitForBit) {
  const testing::AnalyticWall wall = testing::refined(testing::vGroove(), 0.0037, 0.6);
  const TriangleMesh mesh = testing::meshWall(wall);
  const TriangleIndex index(mesh, std::vector<std::uint32_t>(mesh.triangles.size(), 0));
  const DepthCameraParams camera;
  const Pose T_F_C = testing::pose(0.013, -0.021, 0.0, 2.0, -1.0, 30.0);
  std::vector<std::vector<float>> images;
  for (const RasterKernel kernel : {RasterKernel::kGeneric, RasterKernel::kAvx2, RasterKernel::kAvx512}) {
    if (!rasterKernelSupported(kernel)) continue;
    std::vector<float> z(static_cast<std::size_t>(camera.width_px) * camera.height_px,
                         -std::numeric_limits<float>::infinity());
    rasterizeDepth(index, T_F_C.inverse(), camera, {}, z, kernel);
    images.push_back(z);
  }
  ASSERT_GE(images.size(), 1u);
  for (std::size_t k = 1; k < images.size(); ++k) EXPECT_EQ(images[k], images[0]) << "variant " << k;
  for (int r = 0; r < camera.height_px; ++r) {
    for (int c = 0; c < camera.width_px; ++c) {
      const float h = std::max(images[0][static_cast<std::size_t>(r) * camera.width_px + c], float(camera.far_m));
      ASSERT_NEAR(h, testing::expectedDepth(wall, T_F_C, camera, r, c), kTolerance_m) << r << "," << c;
    }
  }
}

}  // namespace
}  // namespace climbsim::scene
