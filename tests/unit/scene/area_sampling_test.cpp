// Area-weighted depth pixels (DepthCameraParams::samples_per_pixel): a pixel an edge crosses
// holds the share of its square on each side (so the image follows the camera's pose within
// 1/n of a pixel, not in whole pixels), a plane keeps its centre heights, and tiles, masked or
// not, hold the whole image's pixels and support heights bit for bit.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "analytic_scenes.hpp"
#include "area_sampling.hpp"
#include "render_scene.hpp"

namespace climbsim::scene {
namespace {

using testing::pose;

constexpr int kSamples = 16;

DepthCameraParams smallCamera(int side_px, double pixel_m) { return testing::sampledCamera(side_px, pixel_m, kSamples); }

TEST(AreaSampling, OffsetsAreAnNRooksPatternAboutTheCentre) {
  for (const int n : {1, 2, 5, 8, 16, 64}) {
    const auto offsets = subpixelOffsets(n);
    ASSERT_EQ(offsets.size(), static_cast<std::size_t>(n));
    std::set<double> xs, ys;
    double sx = 0.0, sy = 0.0;
    for (const auto& [dx, dy] : offsets) {
      EXPECT_GT(dx, -0.5);
      EXPECT_LT(dx, 0.5);
      EXPECT_GT(dy, -0.5);
      EXPECT_LT(dy, 0.5);
      xs.insert(dx);
      ys.insert(dy);
      sx += dx;
      sy += dy;
    }
    EXPECT_EQ(xs.size(), offsets.size()) << n << " points: two share a column offset";
    EXPECT_EQ(ys.size(), offsets.size()) << n << " points: two share a row offset";
    EXPECT_NEAR(sx, 0.0, 1e-12);
    EXPECT_NEAR(sy, 0.0, 1e-12);
  }
}

TEST(AreaSampling, AStepsRowFollowsTheEdgeWithinASixteenthOfAPixelAsTheCameraMoves) {
  // step(): 0.011 m left of x = 0.0731, -0.0123 m right of it. Along a row, the sum of the
  // pixels' shares of the high side is the edge's distance from the image's left border [px].
  const testing::AnalyticWall wall = testing::step();
  const double high = 0.011, low = -0.0123, edge_x = 0.0731;
  for (const DepthBackend backend : {DepthBackend::kRasterizer, DepthBackend::kEmbree}) {
    RenderScene scene(testing::meshWall(wall));
    const DepthCameraParams camera = smallCamera(32, 0.002);
    for (int k = 0; k < 40; ++k) {
      const double x_m = 0.0731 - 0.001 + k * camera.pixel_size_m / 40.0;
      DepthImage image;
      scene.renderDepth(pose(x_m, 0.01, 0.0, 0, 0, 0), camera, {}, backend, image);
      const double expected_px = (edge_x - x_m + 0.5 * camera.width_px * camera.pixel_size_m) / camera.pixel_size_m;
      for (const int row : {0, 13, 31}) {
        double high_px = 0.0;
        for (int col = 0; col < camera.width_px; ++col) high_px += (image.at(row, col) - low) / (high - low);
        EXPECT_NEAR(high_px, expected_px, 1.0 / kSamples + 1e-4)
            << toString(backend) << ", camera at x = " << x_m << " m, row " << row;
      }
    }
  }
}

// Centre heights whose second differences lie at the threshold to within float rounding (and
// far from it), on a plane of large heights and near zero: every row kernel decides each pixel
// as the double expressions do, inner pixels and border pixels, tiles and masks alike.
TEST(AreaSampling, EveryKernelVariantDecidesTheEdgePixelsAsTheDoubleExpressions) {
  constexpr int W = 83, H = 41;  // rows longer than a vector, a tail of odd length
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<float> centre(static_cast<std::size_t>(W) * H);
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      const double base = (r % 3 == 0 ? 0.049 : 1e-4) * unit(rng);
      // Every other pixel of a row a kink of about the threshold (2 mm): tiny offsets decide it.
      const double kink = c % 2 == 0 ? kEdgeThreshold_m / 2.0 * (1.0 + 1e-6 * unit(rng)) : 0.0;
      centre[static_cast<std::size_t>(r) * W + c] = static_cast<float>(r % 5 == 4 ? base : 1e-7 * r + kink);
    }
  }
  std::vector<std::uint32_t> picked;
  for (std::uint32_t i = 0; i < W * H; i += 3) picked.push_back(i);
  const PixelMask mask(W, H, picked);
  struct Region {
    int row0, col0, rows, cols;
    const PixelMask* mask;
  };
  for (const Region& region : {Region{0, 0, H, W, nullptr}, Region{3, 7, 30, 60, nullptr}, Region{0, 0, H, W, &mask}}) {
    const std::vector<std::uint32_t> expected = edgePixels(centre, W, H, region.row0, region.col0, region.rows,
                                                           region.cols, region.mask, kEdgeThreshold_m, true);
    EXPECT_GT(expected.size(), 100u);
    EXPECT_LT(expected.size(), static_cast<std::size_t>(region.rows) * region.cols - 100u);
    for (const RasterKernel kernel : {RasterKernel::kGeneric, RasterKernel::kAvx2, RasterKernel::kAvx512}) {
      if (!rasterKernelSupported(kernel)) continue;
      EXPECT_EQ(edgePixels(centre, W, H, region.row0, region.col0, region.rows, region.cols, region.mask,
                           kEdgeThreshold_m, false, kernel),
                expected)
          << "kernel " << static_cast<int>(kernel) << ", tile at row " << region.row0 << (region.mask ? ", masked" : "");
    }
  }
}

TEST(AreaSampling, APlaneKeepsItsCentreHeights) {
  RenderScene scene(testing::meshWall(testing::refined(testing::tiltedPlane(), 0.004, 0.3)));
  DepthCameraParams camera = smallCamera(64, 0.003);
  const Pose T_W_C = pose(0.01, -0.02, 0.0, 0, 0, 30.0);
  const DepthImage area = scene.renderDepth(T_W_C, camera);
  camera.samples_per_pixel = 1;
  const DepthImage centre = scene.renderDepth(T_W_C, camera);
  ASSERT_EQ(area.height_m.size(), centre.height_m.size());
  for (std::size_t i = 0; i < area.height_m.size(); ++i) ASSERT_EQ(area.height_m[i], centre.height_m[i]) << i;
}

TEST(AreaSampling, TilesMaskedOrNotHoldTheWholeImagesPixelsAndSupportsBitForBit) {
  // A yawed step and a groove on a mesh of about pixel-sized triangles: edges cross tile borders.
  // With support heights (support_slope > 0) a tile samples the edge pixels around it too.
  testing::AnalyticWall wall = testing::refined(testing::vGroove(), 0.004, 0.4);
  const auto groove = wall.height_m;
  wall.height_m = [groove](double x, double y) { return groove(x, y) + (y > 0.013 ? 0.006 : 0.0); };
  RenderScene scene(testing::meshWall(wall));
  const Pose T_W_C = pose(0.004, 0.002, 0.0, 0, 0, 23.0);
  for (const double support_slope : {0.0, 0.3}) {
    DepthCameraParams camera = smallCamera(96, 0.003);
    camera.support_slope = support_slope;
    const DepthImage whole = scene.renderDepth(T_W_C, camera);
    EXPECT_EQ(whole.support_px.empty(), support_slope == 0.0);
    std::vector<std::uint32_t> picked;
    for (std::uint32_t i = 0; i < 96u * 96u; i += 7) picked.push_back(i);
    const auto mask = std::make_shared<const PixelMask>(96, 96, picked);
    for (const PixelTile& tile : {PixelTile{0, 0, 48, 96}, PixelTile{31, 17, 40, 50}, PixelTile{95, 0, 1, 96},
                                  PixelTile{0, 0, 96, 96, mask}, PixelTile{10, 20, 60, 70, mask}}) {
      camera.tile = tile;
      const DepthImage part = scene.renderDepth(T_W_C, camera);
      const std::string where = "tile rows " + std::to_string(tile.row0) + "+" + std::to_string(tile.rows) +
                                " cols " + std::to_string(tile.col0) + "+" + std::to_string(tile.cols) +
                                ", support_slope " + std::to_string(support_slope);
      std::vector<std::uint32_t> want_px;
      std::vector<float> want_m;
      for (std::size_t i = 0; i < whole.support_px.size(); ++i) {
        const int r = static_cast<int>(whole.support_px[i]) / 96, c = static_cast<int>(whole.support_px[i]) % 96;
        if (r < tile.row0 || r >= tile.row0 + tile.rows || c < tile.col0 || c >= tile.col0 + tile.cols) continue;
        if (tile.mask && !mask->contains(r, c)) continue;
        want_px.push_back(whole.support_px[i]);
        want_m.push_back(whole.support_m[i]);
      }
      EXPECT_EQ(part.support_px, want_px) << where;
      ASSERT_EQ(part.support_m.size(), want_m.size()) << where;
      EXPECT_EQ(std::memcmp(part.support_m.data(), want_m.data(), want_m.size() * sizeof(float)), 0) << where;
      for (int r = tile.row0; r < tile.row0 + tile.rows; ++r) {
        for (int c = tile.col0; c < tile.col0 + tile.cols; ++c) {
          if (tile.mask && !mask->contains(r, c)) continue;
          const float a = part.at(r, c), b = whole.at(r, c);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "pixel (" << r << ", " << c << ") of " << where;
        }
      }
    }
  }
}

}  // namespace
}  // namespace climbsim::scene
