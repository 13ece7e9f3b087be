// Support heights (docs/design.md#sub-pixel-leakage): over a straight edge the strip's sag
// starts within 1/16 px of the edge, wherever it lies in its pixel, and a plane or a concave
// slope below max_slope gives no support above a pixel's mean (its gap stays what it was).
// Tiles carry the whole image's supports: area_sampling_test.cpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "analytic_scenes.hpp"
#include "area_sampling.hpp"
#include "render_scene.hpp"

namespace climbsim::scene {
namespace {

using testing::pose;

constexpr int kSamples = 16;
constexpr double kMaxSlope = 0.3;

DepthCameraParams supportCamera(int side_px, double pixel_m) {
  return testing::sampledCamera(side_px, pixel_m, kSamples, kMaxSlope);
}

TEST(SupportHeight, APlaneOfSlopeBelowMaxSlopeNeverRisesAboveItsMean) {
  const auto offsets = subpixelOffsets(kSamples);
  const double s = 0.003;
  for (const double slope : {0.0, 0.05, 0.2, 0.29}) {
    for (const double angle_deg : {0.0, 17.0, 45.0, 90.0, 133.0}) {
      const double ux = std::cos(angle_deg * M_PI / 180.0), uy = std::sin(angle_deg * M_PI / 180.0);
      std::vector<double> z;
      double sum = 0.0;
      for (const auto& [dx, dy] : offsets) {
        z.push_back(0.0017 + slope * s * (dx * ux + dy * uy));
        sum += z.back();
      }
      const double mean = sum / kSamples;
      // Along the gradient, or none (edgeNormal of a plane, which does not bend).
      for (const auto& normal : {std::make_pair(ux * slope, uy * slope), std::make_pair(0.0, 0.0)}) {
        const double support = supportHeight_m(z, offsets, normal, kMaxSlope, s);
        EXPECT_LE(static_cast<float>(support), static_cast<float>(mean))
            << "slope " << slope << " at " << angle_deg << " deg, normal (" << normal.first << ", " << normal.second
            << ")";
      }
    }
  }
}

TEST(SupportHeight, AConcaveSlopeBelowMaxSlopeHasEdgePixelsButNoSupport) {
  // z = 0.2 |x - x0|: the pixels along the valley's axis bend by 2.4 mm (edge pixels, sampled
  // over their squares) and hold their mean, which the strip can only fall below.
  testing::AnalyticWall wall;
  constexpr double kAxis = 0.0113;
  wall.height_m = [](double x, double) { return 0.2 * std::abs(x - kAxis) - 0.01; };
  wall.x_lines = {-1.0, kAxis, 1.0};
  wall.y_lines = {-1.0, 1.0};
  RenderScene scene(testing::meshWall(testing::refined(wall, 0.006, 0.3)));
  DepthCameraParams camera = supportCamera(32, 0.006);
  const Pose T_W_C = pose(0.002, -0.004, 0.0, 0, 0, 11.0);
  const DepthImage with = scene.renderDepth(T_W_C, camera);
  camera.samples_per_pixel = 1;
  const DepthImage centres = scene.renderDepth(T_W_C, camera);
  std::size_t sampled = 0;
  for (std::size_t i = 0; i < with.height_m.size(); ++i) sampled += with.height_m[i] != centres.height_m[i] ? 1 : 0;
  EXPECT_GT(sampled, 10u) << "the valley's pixels must be edge pixels";
  EXPECT_TRUE(with.support_px.empty()) << with.support_px.size() << " supports, the first at raster "
                                       << (with.support_px.empty() ? 0u : with.support_px.front());
}

TEST(SupportHeight, OverAStepTheSagStartsWithinASixteenthOfAPixelOfTheEdge) {
  // step(): 0.011 m left of x = 0.0731, -0.0123 m right of it. The strip held by the high side
  // stands at high - max_slope * (x_c - edge) at a centre x_c past the edge, at high before it.
  const double high = 0.011, edge_x = 0.0731;
  for (const DepthBackend backend : {DepthBackend::kRasterizer, DepthBackend::kEmbree}) {
    RenderScene scene(testing::meshWall(testing::step()));
    const DepthCameraParams camera = supportCamera(32, 0.003);
    const double s = camera.pixel_size_m;
    for (int k = 0; k < 48; ++k) {
      const double x_m = edge_x - 0.0015 + k * s / 48.0;
      DepthImage image;
      scene.renderDepth(pose(x_m, 0.01, 0.0, 0, 0, 0), camera, {}, backend, image);
      const double edge_px = (edge_x - x_m + 0.5 * camera.width_px * s) / s;  // from the left border
      // The first pixel whose centre lies past the edge: the sag must start there.
      const int first_past = static_cast<int>(std::floor(edge_px + 0.5));
      ASSERT_EQ(image.support_px.size(), image.support_m.size());
      std::vector<int> rows_with_first(camera.height_px, 0);
      for (std::size_t i = 0; i < image.support_px.size(); ++i) {
        const int r = static_cast<int>(image.support_px[i]) / camera.width_px;
        const int c = static_cast<int>(image.support_px[i]) % camera.width_px;
        const double expected_m = high - kMaxSlope * s * std::max(0.0, c + 0.5 - edge_px);
        EXPECT_LE(std::abs(c + 0.5 - edge_px), 1.5) << toString(backend) << ", x = " << x_m << ": a support far away";
        EXPECT_LE(image.support_m[i], expected_m + 1e-6) << toString(backend) << ", x = " << x_m << ", row " << r;
        EXPECT_GE(image.support_m[i], expected_m - kMaxSlope * s / kSamples - 1e-6)
            << toString(backend) << ", x = " << x_m << ", row " << r << ", col " << c
            << ": the sag starts more than 1/16 px past the edge";
        rows_with_first[r] += c == first_past ? 1 : 0;
      }
      for (int r = 0; r < camera.height_px; ++r) {
        EXPECT_EQ(rows_with_first[r], 1) << toString(backend) << ", x = " << x_m << ", row " << r
                                         << ": no support at the first pixel past the edge";
      }
    }
  }
}

TEST(SupportHeight, WithoutASlopeNoSupportIsGivenAndTheHeightsAreTheSame) {
  RenderScene scene(testing::meshWall(testing::step()));
  DepthCameraParams camera = supportCamera(32, 0.003);
  const Pose T_W_C = pose(0.0731 + 0.0007, 0.01, 0.0, 0, 0, 0);
  const DepthImage with = scene.renderDepth(T_W_C, camera);
  camera.support_slope = 0.0;
  const DepthImage without = scene.renderDepth(T_W_C, camera);
  EXPECT_FALSE(with.support_px.empty());
  EXPECT_TRUE(without.support_px.empty());
  ASSERT_EQ(with.height_m.size(), without.height_m.size());
  EXPECT_EQ(std::memcmp(with.height_m.data(), without.height_m.data(), with.height_m.size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace climbsim::scene
