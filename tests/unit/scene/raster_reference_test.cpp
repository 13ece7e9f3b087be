// The rasteriser's default path against its reference path (RenderOptions::reference_raster):
// the same depth image bit for bit on many camera poses, whole, as tiles with and without a
// mask (scattered blocks, thin bands, rings, single pixels), with area-weighted edge pixels,
// with every kernel variant this CPU runs.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "analytic_scenes.hpp"
#include "render_scene.hpp"

namespace climbsim::scene {
namespace {

using testing::pose;

// A pylon face as the default scene has it: rough, pixel-sized and larger triangles, a
// crack's walls (edge pixels), a step, placed far from the world origin; a box on it as a
// moving body (seen) and a second one excluded.
TriangleMesh roughFace(const Pose& T_W_F) {
  testing::AnalyticWall wall = testing::refined(testing::vGroove(), 0.0049, 0.6);
  const auto groove = wall.height_m;
  wall.height_m = [groove](double x, double y) {
    return groove(x, y) + 0.0011 * std::sin(230.0 * x + 0.7) * std::cos(170.0 * y) + 0.002 * x - 0.003 * y +
           (y > 0.1 ? 0.004 : 0.0);
  };
  TriangleMesh out;
  testing::appendMesh(out, testing::meshWall(wall), T_W_F);
  return out;
}

RenderScene sceneOf(const TriangleMesh& mesh, const Pose& T_W_F, bool reference, RasterKernel kernel) {
  RenderOptions options;
  options.reference_raster = reference;
  options.raster_kernel = kernel;
  RenderScene scene(mesh, options);
  scene.addBody(testing::box({-0.02, -0.03, -0.01}, {0.05, 0.04, 0.02}, 7), T_W_F * pose(0.11, -0.07, 0.0, 0, 0, 25.0));
  scene.addBody(testing::box({-0.03, -0.03, -0.01}, {0.03, 0.03, 0.03}, 8), T_W_F * pose(-0.09, 0.05, 0.0, 0, 0, 0.0));
  return scene;
}

// Poses over the face: yawed any way, tilted by up to 2°, the sealing plane a few mm off the wall.
std::vector<Pose> cameraPoses(const Pose& T_W_F, int count) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Pose> poses;
  for (int k = 0; k < count; ++k) {
    const double yaw = k % 4 == 0 ? -90.0 : 180.0 * unit(rng);  // a quarter aligned with the grid
    poses.push_back(T_W_F * pose(0.1 * unit(rng), 0.1 * unit(rng), 0.003 * unit(rng), 2.0 * unit(rng) * (k % 3 != 0),
                                 2.0 * unit(rng) * (k % 3 != 0), yaw));
  }
  return poses;
}

std::string differences(const DepthImage& a, const DepthImage& b) {
  if (a.height_m.size() != b.height_m.size()) return "sizes differ";
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.height_m.size(); ++i) {
    differ += std::memcmp(&a.height_m[i], &b.height_m[i], sizeof(float)) != 0;
  }
  if (differ != 0) return std::to_string(differ) + " pixels differ";
  if (a.support_px != b.support_px || a.support_m.size() != b.support_m.size() ||
      std::memcmp(a.support_m.data(), b.support_m.data(), a.support_m.size() * sizeof(float)) != 0) {
    return "support heights differ";
  }
  return "";
}

// A mask of scattered blocks and single pixels (as a sealing shard's strips).
std::shared_ptr<const PixelMask> scatteredMask(const DepthCameraParams& camera) {
  std::vector<std::uint32_t> pixels;
  for (int r = 0; r < camera.height_px; ++r) {
    for (int c = 0; c < camera.width_px; ++c) {
      if ((r / 7 + c / 11) % 5 == 0 || (r * 31 + c * 17) % 97 == 0) {
        pixels.push_back(static_cast<std::uint32_t>(r * camera.width_px + c));
      }
    }
  }
  return std::make_shared<const PixelMask>(camera.width_px, camera.height_px, pixels);
}

TEST(RasterReference, TheDefaultPathGivesTheReferenceImageBitForBitOnManyPoses) {
  const Pose T_W_F = pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0) * pose(0, 0, 0, 0, 0, 180.0);
  const TriangleMesh mesh = roughFace(T_W_F);
  RenderScene fast = sceneOf(mesh, T_W_F, false, RasterKernel::kAuto);
  RenderScene reference = sceneOf(mesh, T_W_F, true, RasterKernel::kAuto);
  DepthCameraParams camera;
  DepthCameraParams tile = camera;
  tile.tile = PixelTile{37, 5, 120, 200};
  DepthCameraParams masked = camera;
  masked.tile = PixelTile{20, 30, 200, 190, scatteredMask(camera)};
  const std::vector<std::uint32_t> excluded{8};
  int edge_frames = 0;
  std::size_t supports = 0;
  std::uint64_t sample_set_ups = 0, sample_handed = 0;
  for (const Pose& T_W_C : cameraPoses(T_W_F, 60)) {
    for (const DepthCameraParams* params : {&camera, &tile, &masked}) {
      const DepthImage a = fast.renderDepth(T_W_C, *params, excluded);
      const DepthImage b = reference.renderDepth(T_W_C, *params, excluded);
      ASSERT_EQ(differences(a, b), "") << "tile " << params->tile.row0 << "," << params->tile.col0;
      ASSERT_EQ(fast.lastDepthCounters().leaves > 0, reference.lastDepthCounters().leaves > 0);
    }
    // The work of the default path is at most the reference's (batches outside the view culled).
    EXPECT_LE(fast.lastDepthCounters().triangles, reference.lastDepthCounters().triangles);
    DepthCameraParams subpixel = camera;
    subpixel.samples_per_pixel = 16;
    subpixel.support_slope = 0.3;
    const DepthImage a = fast.renderDepth(T_W_C, subpixel, excluded);
    const RasterCounters with_samples = fast.lastDepthCounters();
    const DepthImage b = reference.renderDepth(T_W_C, subpixel, excluded);
    ASSERT_EQ(differences(a, b), "") << "16 samples per edge pixel, support heights";
    supports += a.support_px.size();
    const DepthImage centre = fast.renderDepth(T_W_C, camera, excluded);
    edge_frames += differences(a, centre) != "";  // the crack and the step make edge pixels
    // The sample passes set up a part of the triangles handed to them (those beyond the centre
    // pass's), each once for all 16 samples.
    const std::uint64_t handed = with_samples.triangles - fast.lastDepthCounters().triangles;
    EXPECT_LE(with_samples.sample_triangles_set_up, handed);
    sample_set_ups += with_samples.sample_triangles_set_up;
    sample_handed += handed;
  }
  EXPECT_GT(edge_frames, 30);
  EXPECT_GT(supports, 0u);
  EXPECT_GT(sample_set_ups, 0u);
  EXPECT_LT(sample_set_ups, sample_handed);
}

TEST(RasterReference, EveryKernelVariantOfTheDefaultPathGivesTheReferenceImage) {
  const Pose T_W_F = pose(-1.3, 4.1, 0.6, 90.0, 0.0, 90.0);
  const TriangleMesh mesh = roughFace(T_W_F);
  RenderScene reference = sceneOf(mesh, T_W_F, true, RasterKernel::kGeneric);
  DepthCameraParams camera;
  camera.samples_per_pixel = 5;
  camera.tile = PixelTile{3, 60, 250, 150, scatteredMask(camera)};
  const std::vector<Pose> poses = cameraPoses(T_W_F, 8);
  for (const RasterKernel kernel : {RasterKernel::kGeneric, RasterKernel::kAvx2, RasterKernel::kAvx512}) {
    if (!rasterKernelSupported(kernel)) continue;
    RenderScene fast = sceneOf(mesh, T_W_F, false, kernel);
    for (const Pose& T_W_C : poses) {
      for (const PixelTile& t : {PixelTile{}, camera.tile}) {
        DepthCameraParams params = camera;
        params.tile = t;
        ASSERT_EQ(differences(fast.renderDepth(T_W_C, params, {}), reference.renderDepth(T_W_C, params, {})), "")
            << "kernel " << static_cast<int>(kernel);
      }
    }
  }
}

// Masks as a sealing shard's strips look to the culling by the mask's pixels: thin bands along
// the rows, the columns and a diagonal, a ring, single scattered pixels, the image's last row and
// column and its corners.
std::vector<std::shared_ptr<const PixelMask>> thinMasks(const DepthCameraParams& camera) {
  const int W = camera.width_px, H = camera.height_px;
  std::vector<std::vector<std::uint32_t>> sets(5);
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      const auto raster = static_cast<std::uint32_t>(r * W + c);
      if (r == 100 || (c >= 40 && c < 43) || std::abs(r - c - 10) <= 1) sets[0].push_back(raster);
      const double d = std::hypot(r - 128.5, c - 121.0);
      if (d >= 60.0 && d < 61.5) sets[1].push_back(raster);
      if ((r * 131 + c * 71) % 53 == 0) sets[2].push_back(raster);
      if (r == H - 1 || c == W - 1 || (r < 2 && c < 2)) sets[3].push_back(raster);
      if ((r % 16 == 3 && c % 5 == 0) || (c % 16 == 9 && r % 6 == 1)) sets[4].push_back(raster);
    }
  }
  std::vector<std::shared_ptr<const PixelMask>> masks;
  for (const auto& pixels : sets) masks.push_back(std::make_shared<const PixelMask>(W, H, pixels));
  return masks;
}

TEST(RasterReference, CullingByTheMasksPixelsDropsNoTriangleThatWritesOne) {
  const Pose T_W_F = pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0) * pose(0, 0, 0, 0, 0, 180.0);
  const TriangleMesh mesh = roughFace(T_W_F);
  RenderScene reference = sceneOf(mesh, T_W_F, true, RasterKernel::kGeneric);
  DepthCameraParams camera;
  const auto masks = thinMasks(camera);
  const std::vector<Pose> poses = cameraPoses(T_W_F, 12);
  for (const RasterKernel kernel : {RasterKernel::kGeneric, RasterKernel::kAvx2, RasterKernel::kAvx512}) {
    if (!rasterKernelSupported(kernel)) continue;
    RenderScene fast = sceneOf(mesh, T_W_F, false, kernel);
    std::uint64_t set_up = 0, handed = 0;
    for (std::size_t m = 0; m < masks.size(); ++m) {
      for (std::size_t p = 0; p < poses.size(); ++p) {
        DepthCameraParams params = camera;
        params.tile = m % 2 == 0 ? PixelTile{0, 0, camera.height_px, camera.width_px, masks[m]}
                                 : PixelTile{1, 2, camera.height_px - 1, camera.width_px - 3, masks[m]};
        if (p % 3 == 1) {
          params.samples_per_pixel = 16;
          params.support_slope = 0.3;
        }
        const DepthImage a = fast.renderDepth(poses[p], params, {8});
        ASSERT_EQ(differences(a, reference.renderDepth(poses[p], params, {8})), "")
            << "kernel " << static_cast<int>(kernel) << ", mask " << m << ", pose " << p;
        if (params.samples_per_pixel == 1) {
          set_up += fast.lastDepthCounters().triangles_set_up;
          handed += fast.lastDepthCounters().triangles;
        }
      }
    }
    // Most triangles handed over near a thin mask cover none of its pixels.
    EXPECT_GT(set_up, 0u);
    EXPECT_LT(2 * set_up, handed) << "kernel " << static_cast<int>(kernel);
  }
}

}  // namespace
}  // namespace climbsim::scene
