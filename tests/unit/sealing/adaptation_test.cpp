// The sealing adaptation: the production algorithm reaches the oracle's fixpoint bit for bit
// on random rough surfaces with cracks, holes and steps; the oracle's result is the least
// slope-limited sealing above the ground.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "adaptation.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"

namespace climbsim::sealing::testing {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectProductionEqualsOracle(const PixelGrid& g, double slope, std::uint64_t first_seed, int seeds) {
  const StripMasks masks(geometry(), g, "test");
  const Neighbourhood nbh(slope, g.pixel_size_m);
  const SealingAdapter adapter(masks, nbh);
  int raised_frames = 0;
  for (std::uint64_t seed = first_seed; seed < first_seed + seeds; ++seed) {
    const DepthGrid depth = randomSurface(g, seed);
    int passes = 0;
    const auto oracle = adaptNaive(masks, nbh, depth.height_m, &passes);
    const auto production = adapter.adapt(depth.height_m);
    ASSERT_EQ(oracle.size(), production.size());
    for (std::size_t k = 0; k < oracle.size(); ++k) {
      ASSERT_TRUE(sameBits(oracle[k], production[k]))
          << "seed " << seed << " slope " << slope << " grid " << g.width_px << "x" << g.height_px << " sealing pixel "
          << k << ": oracle " << oracle[k] << " production " << production[k];
    }
    raised_frames += passes > 1 ? 1 : 0;
  }
  // The surfaces must exercise the adaptation, not only pass flat walls through.
  EXPECT_GT(raised_frames, seeds * 3 / 4);
}

TEST(Adaptation, ProductionEqualsOracleOnRandomSurfaces128) { expectProductionEqualsOracle(grid(128, 128), 0.3, 1, 60); }

TEST(Adaptation, ProductionEqualsOracleOnRandomSurfaces256) { expectProductionEqualsOracle(grid(256, 256), 0.3, 1000, 20); }

TEST(Adaptation, ProductionEqualsOracleOnANonSquareGrid) {
  // Taller than wide: mixing up rows and columns would break the neighbour lists.
  expectProductionEqualsOracle(PixelGrid{200, 240, 0.8 / 200}, 0.3, 2000, 20);
}

TEST(Adaptation, ProductionEqualsOracleForSteepAndFlatSlopes) {
  expectProductionEqualsOracle(grid(160, 160), 0.05, 3000, 15);
  expectProductionEqualsOracle(grid(160, 160), 2.0, 4000, 15);
}

TEST(Adaptation, OracleGivesTheLeastSlopeLimitedSealingAboveTheGround) {
  const PixelGrid g = grid(128, 128);
  const StripMasks masks(geometry(), g, "test");
  const Neighbourhood nbh(0.3, g.pixel_size_m);
  for (std::uint64_t seed = 50; seed < 60; ++seed) {
    const DepthGrid depth = randomSurface(g, seed);
    const auto h = adaptNaive(masks, nbh, depth.height_m);
    const auto& pixels = masks.sealingPixels();
    for (std::size_t k = 0; k < pixels.size(); ++k) {
      const double ground = depth.height_m[pixels[k]];
      ASSERT_GE(h[k], ground);
      const int r = static_cast<int>(pixels[k] / g.width_px), c = static_cast<int>(pixels[k] % g.width_px);
      bool tight = h[k] == ground;
      for (std::size_t j = 0; j < 8; ++j) {
        const int nr = r + Neighbourhood::kOffsets[j][0], nc = c + Neighbourhood::kOffsets[j][1];
        if (nr < 0 || nc < 0 || nr >= g.height_px || nc >= g.width_px) continue;
        const auto n = masks.sealingIndexOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
        if (n < 0) continue;
        // Slope-limited: no neighbour more than a step above.
        ASSERT_LE(h[n] - nbh.step_m[j], h[k]) << "seed " << seed;
        tight = tight || h[n] - nbh.step_m[j] == h[k];
      }
      // Least: a raised pixel is held up by a neighbour exactly one step higher.
      ASSERT_TRUE(tight) << "seed " << seed << " pixel " << k << " raised without cause";
    }
  }
}

TEST(Adaptation, AVerticalWalledCrackIsBridgedBySlopeTimesDistanceToItsEdge) {
  // A crack 20 mm deep, 30 mm wide, vertical walls, along x through the centre: it crosses
  // outer1 where that strip runs along y, so within a column the shortest path from a crack
  // pixel to the wall is straight up or down: h_s = max(-depth, -m * slope * s) for a pixel m
  // rows from the nearest row outside the crack.
  const PixelGrid g = grid(256, 256);
  const StripMasks masks(geometry(), g, "test");
  const Neighbourhood nbh(0.3, g.pixel_size_m);
  DepthGrid depth = flatWall(g);
  Crack crack;
  crack.bottom_width_m = 0.03;
  crack.depth_m = 0.02;
  addCrack(depth, crack);
  const auto h = SealingAdapter(masks, nbh).adapt(depth.height_m);
  const int outer1 = 0;
  int checked = 0;
  for (int c = 0; c < g.width_px; ++c) {
    int top = -1, bottom = -1;  // first and last crack row of this column
    for (int r = 0; r < g.height_px; ++r) {
      if (depth.height_m[static_cast<std::size_t>(r) * g.width_px + c] < 0) {
        if (top < 0) top = r;
        bottom = r;
      }
    }
    auto inOuter1 = [&](int r) { return masks.segmentOfPixel(static_cast<std::size_t>(r) * g.width_px + c) == outer1; };
    // Only columns where the strip covers the crack and a few rows on both sides.
    bool covered = top > 3 && bottom + 3 < g.height_px;
    for (int r = top - 3; covered && r <= bottom + 3; ++r) covered = inOuter1(r);
    if (!covered) continue;
    for (int r = top; r <= bottom; ++r) {
      const int m = std::min(r - top + 1, bottom + 1 - r);
      const double expected = std::max(static_cast<double>(static_cast<float>(-crack.depth_m)), -m * nbh.step_m[0]);
      const auto k = masks.sealingIndexOfPixel(static_cast<std::size_t>(r) * g.width_px + c);
      EXPECT_NEAR(h[k], expected, 1e-12) << "row " << r << " col " << c;
      ++checked;
    }
    for (const int r : {top - 1, bottom + 1}) {
      EXPECT_EQ(h[masks.sealingIndexOfPixel(static_cast<std::size_t>(r) * g.width_px + c)], 0.0);
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(Adaptation, ProductionEqualsOracleWithSupportHeights) {
  for (const PixelGrid& g : {grid(128, 128), PixelGrid{200, 240, 0.8 / 200}}) {
    const StripMasks masks(geometry(), g, "test");
    const Neighbourhood nbh(0.3, g.pixel_size_m);
    const SealingAdapter adapter(masks, nbh);
    std::size_t lifted = 0;
    for (std::uint64_t seed = 7000; seed < 7020; ++seed) {
      DepthGrid depth = randomSurface(g, seed);
      addSupports(depth, seed);
      const auto oracle = adaptNaive(masks, nbh, depth.height_m, nullptr, &depth.supports);
      const auto plain = adaptNaive(masks, nbh, depth.height_m);
      std::vector<double> production;
      adapter.adapt(depth.height_m, -std::numeric_limits<double>::infinity(), production, nullptr, &depth.supports);
      ASSERT_EQ(oracle.size(), production.size());
      for (std::size_t k = 0; k < oracle.size(); ++k) {
        ASSERT_TRUE(sameBits(oracle[k], production[k]))
            << "seed " << seed << " sealing pixel " << k << ": oracle " << oracle[k] << " production " << production[k];
        ASSERT_GE(oracle[k], plain[k]);
        lifted += oracle[k] > plain[k] ? 1 : 0;
      }
    }
    // The supports must raise the sealing somewhere, or the comparison proves nothing.
    EXPECT_GT(lifted, 100u);
  }
}

/// The 16 sample offsets along one axis of the scene's n-rooks pattern [px] (each row and
/// each column offset once: services/scene/render/depth_camera.hpp subpixelOffsets).
std::vector<double> rookOffsets() {
  std::vector<double> o;
  for (int k = 0; k < 16; ++k) o.push_back((k + 0.5) / 16.0 - 0.5);
  return o;
}

TEST(Adaptation, OverACrackEdgeInsideAPixelTheSagStartsWithinASixteenthOfAPixelOfTheEdge) {
  // A crack 20 mm deep along x with vertical walls at sub-pixel rows, under outer1 where that
  // strip runs along y (as above). The scene gives each edge pixel h_g, the mean of 16 samples
  // over its square, and the support max_i (z_i - m s d_i) over the samples of the pixel and its
  // neighbours, d_i the distance of sample i from the pixel's centre across the edge. The
  // continuous strip held at the walls stands at max(-depth, -m * distance to the nearer wall)
  // at a pixel's centre; the adaptation must give that within m s / 16, and does not without
  // the supports (the sag then starts at the centre of the last pixel whose centre is on the
  // wall).
  const PixelGrid g = grid(256, 256);
  const double s = g.pixel_size_m, m = 0.3, depth_m = 0.02;
  const StripMasks masks(geometry(), g, "test");
  const Neighbourhood nbh(m, s);
  const SealingAdapter adapter(masks, nbh);
  const auto inf = std::numeric_limits<double>::infinity();
  const int outer1 = 0;
  int checked = 0;
  double worst_without = 0.0;
  // Walls anywhere in their pixels, also closer to a border than any sample line of the pixel.
  for (const double fraction : {0.02, 0.21, 0.5, 0.77, 0.985}) {
    // Crack rows: y in (y_lo, y_hi), both walls inside pixels.
    const double y_hi = g.yOfRow_m(125) + (0.5 - fraction) * s;
    const double y_lo = y_hi - 0.0301;
    DepthGrid depth = flatWall(g);
    const auto inCrack = [&](double y) { return y > y_lo && y < y_hi; };
    for (int r = 0; r < g.height_px; ++r) {
      double sum = 0.0, support = -inf;
      for (const double dy : rookOffsets()) sum += inCrack(g.yOfRow_m(r) - dy * s) ? -depth_m : 0.0;
      // The support: from the wall samples of the pixel and of its neighbours (the scene's
      // edge pixels bound their own and their neighbours' supports), the distance along y.
      for (int p = std::max(0, r - 1); p <= std::min(g.height_px - 1, r + 1); ++p) {
        for (const double dy : rookOffsets()) {
          const double y = g.yOfRow_m(p) - dy * s;
          if (!inCrack(y)) support = std::max(support, -m * std::abs(y - g.yOfRow_m(r)));
        }
      }
      const auto mean = static_cast<float>(sum / 16.0);
      for (int c = 0; c < g.width_px; ++c) {
        const auto raster = static_cast<std::uint32_t>(r * g.width_px + c);
        depth.height_m[raster] = mean;
        if (static_cast<float>(support) > mean) {
          depth.supports.raster.push_back(raster);
          depth.supports.height_m.push_back(static_cast<float>(support));
        }
      }
    }
    std::vector<double> with, without;
    adapter.adapt(depth.height_m, -inf, with, nullptr, &depth.supports);
    adapter.adapt(depth.height_m, -inf, without);
    for (int c = 0; c < g.width_px; ++c) {
      const int top = g.height_px / 2 - 8, bottom = g.height_px / 2 + 8;
      bool covered = true;
      for (int r = top; r <= bottom; ++r) {
        covered = covered && masks.segmentOfPixel(static_cast<std::size_t>(r) * g.width_px + c) == outer1;
      }
      if (!covered) continue;
      for (int r = top; r <= bottom; ++r) {
        const double y = g.yOfRow_m(r);
        if (!(y > y_lo && y < y_hi)) continue;
        const double analytic = std::max(-depth_m, -m * std::min(y_hi - y, y - y_lo));
        const auto k = masks.sealingIndexOfPixel(static_cast<std::size_t>(r) * g.width_px + c);
        EXPECT_LE(with[k], analytic + 1e-12) << "fraction " << fraction << " row " << r << " col " << c;
        EXPECT_GE(with[k], analytic - m * s / 16.0 - 1e-12) << "fraction " << fraction << " row " << r << " col " << c;
        worst_without = std::max(worst_without, analytic - without[k]);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 50);
  EXPECT_GT(worst_without, m * s / 4.0) << "without supports the sag starts at a pixel's centre";
}

}  // namespace
}  // namespace climbsim::sealing::testing
