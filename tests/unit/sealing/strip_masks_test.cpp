// The sealing strips rasterised into the pixel grid, by pixel centres and by sub-pixel shares:
// membership, shares and junction rule checked against a brute-force distance to every centre
// line; area; bad grids.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "climbsim/errors.hpp"
#include "sealing_test_robot.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing::testing {
namespace {

double distanceToPolyline_m(double x, double y, const std::vector<RobotGeometry::Point>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const auto& a = line[k];
    const auto& b = line[k + 1];
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
    const double t = std::clamp(((x - a.x_m) * dx + (y - a.y_m) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    best = std::min(best, std::hypot(x - a.x_m - t * dx, y - a.y_m - t * dy));
  }
  return best;
}

TEST(StripMasks, EveryPixelGoesToTheNearestStripWithinHalfAWidth) {
  // Brute force over every centre line. Distances that agree to 1e-12 m are ties up to
  // rounding (the reference computes them in another order): either segment is accepted there.
  constexpr double kRounding_m = 1e-12;
  for (const PixelGrid g : {grid(128, 128), grid(97, 131), grid(200, 200)}) {
    const StripMasks masks(geometry(), g, "test");
    const double half = geometry().strip_width_m / 2;
    std::size_t sealing = 0;
    for (int r = 0; r < g.height_px; ++r) {
      for (int c = 0; c < g.width_px; ++c) {
        std::vector<double> d(geometry().segments.size());
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t s = 0; s < d.size(); ++s) {
          d[s] = distanceToPolyline_m(g.xOfColumn_m(c), g.yOfRow_m(r), geometry().segments[s].centreline_Robot);
          nearest = std::min(nearest, d[s]);
        }
        const std::size_t i = static_cast<std::size_t>(r) * g.width_px + c;
        const int got = masks.segmentOfPixel(i);
        if (std::abs(nearest - half) < kRounding_m) continue;  // on the strip's edge
        if (nearest > half) {
          ASSERT_EQ(got, -1) << "pixel (" << r << ", " << c << ") of " << g.width_px << "x" << g.height_px;
          continue;
        }
        ASSERT_GE(got, 0) << "pixel (" << r << ", " << c << ") of " << g.width_px << "x" << g.height_px;
        ASSERT_LE(d[got], nearest + kRounding_m) << "pixel (" << r << ", " << c << "): not the nearest strip";
        const auto k = masks.sealingIndexOfPixel(i);
        ASSERT_GE(k, 0);
        ASSERT_EQ(masks.sealingPixels()[k], i);
        ++sealing;
      }
    }
    std::size_t listed = 0;
    for (std::size_t s = 0; s < masks.segmentCount(); ++s) listed += masks.segmentPixels(s).size();
    EXPECT_EQ(listed, masks.sealingPixels().size());
    EXPECT_GE(masks.sealingPixels().size(), sealing);
  }
}

TEST(StripMasks, EveryPixelHoldsTheSharesOfItsPointsNearestStripsWithinHalfAWidth) {
  // Brute force over every centre line at each of a pixel's 8 x 8 points, for every 5th pixel.
  // Distances that agree to 1e-12 m are ties up to rounding (the reference computes them in
  // another order): a point there may go either way.
  constexpr double kRounding_m = 1e-12;
  constexpr int kSub = StripMasks::kCoverageSubpixels;
  for (const PixelGrid g : {grid(128, 128), grid(97, 131)}) {
    const StripMasks masks(geometry(), g, "test", StripOutline::kSubpixelShares);
    const double half = geometry().strip_width_m / 2;
    const std::size_t segments = geometry().segments.size();
    for (std::size_t i = 0; i < g.pixelCount(); i += 5) {
      const int r = static_cast<int>(i / g.width_px), c = static_cast<int>(i % g.width_px);
      std::vector<int> points(segments, 0);
      int ambiguous = 0;
      for (int u = 0; u < kSub; ++u) {
        for (int v = 0; v < kSub; ++v) {
          const double x = g.xOfColumn_m(c - 0.5 + (v + 0.5) / kSub), y = g.yOfRow_m(r - 0.5 + (u + 0.5) / kSub);
          std::vector<double> d(segments);
          std::size_t nearest = 0;
          for (std::size_t s = 0; s < segments; ++s) {
            d[s] = distanceToPolyline_m(x, y, geometry().segments[s].centreline_Robot);
            if (d[s] < d[nearest]) nearest = s;
          }
          bool tie = std::abs(d[nearest] - half) < kRounding_m;
          for (std::size_t s = 0; s < segments; ++s) tie = tie || (s != nearest && std::abs(d[s] - d[nearest]) < kRounding_m);
          ambiguous += tie ? 1 : 0;
          if (!tie && d[nearest] <= half) ++points[nearest];
        }
      }
      const auto k = masks.sealingIndexOfPixel(i);
      int total = 0;
      for (std::size_t s = 0; s < segments; ++s) total += points[s];
      if (total == 0 && ambiguous == 0) {
        ASSERT_EQ(k, -1) << "pixel (" << r << ", " << c << ") of " << g.width_px << "x" << g.height_px;
        continue;
      }
      if (k < 0) {
        ASSERT_EQ(total, 0) << "pixel (" << r << ", " << c << ")";
        continue;
      }
      ASSERT_EQ(masks.sealingPixels()[static_cast<std::size_t>(k)], i);
      for (std::size_t s = 0; s < segments; ++s) {
        double share = 0.0;
        const auto& mine = masks.leakPixels(s);
        const auto at = std::lower_bound(mine.begin(), mine.end(), static_cast<std::uint32_t>(k));
        if (at != mine.end() && *at == static_cast<std::uint32_t>(k)) share = masks.leakShares(s)[at - mine.begin()];
        ASSERT_NEAR(share, points[s] / double(kSub * kSub), ambiguous / double(kSub * kSub) + 1e-15)
            << "pixel (" << r << ", " << c << "), segment " << geometry().segments[s].name;
      }
      // It belongs to the segment with the largest share.
      const int owner = masks.segmentOfPixel(i);
      ASSERT_GE(owner, 0);
      for (std::size_t s = 0; s < segments; ++s) ASSERT_LE(points[s], points[owner] + ambiguous) << "pixel (" << r << ", " << c << ")";
    }
    std::size_t listed = 0;
    for (std::size_t s = 0; s < masks.segmentCount(); ++s) listed += masks.segmentPixels(s).size();
    EXPECT_EQ(listed, masks.sealingPixels().size());
  }
}

/// Area of the union of the strips: the outer and inner rings and the radial strips between them [m^2].
double stripsArea_m2() {
  const auto& geo = geometry();
  const double w = geo.strip_width_m;
  const double pi = 3.14159265358979323846;
  return 2 * pi * geo.ring_outer_radius_m * w + 2 * pi * geo.centre_radius_m * w +
         geo.outer_count * (geo.ring_outer_radius_m - geo.centre_radius_m - w) * w;
}

TEST(StripMasks, SealingAreaApproachesTheAreaOfTheStrips) {
  const auto& geo = geometry();
  const double w = geo.strip_width_m;
  const double area_m2 = stripsArea_m2();
  const PixelGrid g = grid(1024, 1024);
  const StripMasks masks(geo, g, "test");
  const double pixels_m2 = masks.sealingPixels().size() * g.pixel_size_m * g.pixel_size_m;
  EXPECT_NEAR(pixels_m2 / area_m2, 1.0, 0.01);
  // Each segment holds about its share: l_i w less what its neighbours take at the ends.
  for (std::size_t s = 0; s < masks.segmentCount(); ++s) {
    const double seg_m2 = masks.segmentPixels(s).size() * g.pixel_size_m * g.pixel_size_m;
    EXPECT_GT(seg_m2, 0.85 * geo.segments[s].length_m * w) << geo.segments[s].name;
    EXPECT_LT(seg_m2, 1.05 * geo.segments[s].length_m * w) << geo.segments[s].name;
  }
}

TEST(StripMasks, SharesAddUpToTheAreaOfTheStripsAtEveryResolution) {
  const auto& geo = geometry();
  const double w = geo.strip_width_m;
  const double area_m2 = stripsArea_m2();
  for (const int px : {256, 1024}) {
    const PixelGrid g = grid(px, px);
    const StripMasks masks(geo, g, "test", StripOutline::kSubpixelShares);
    double shares = 0.0;
    for (std::size_t s = 0; s < masks.segmentCount(); ++s) shares += masks.shareSum(s);
    EXPECT_NEAR(shares * g.pixel_size_m * g.pixel_size_m / area_m2, 1.0, 0.002) << px << " px";
    // Each segment holds about its share: l_i w less what its neighbours take at the ends.
    for (std::size_t s = 0; s < masks.segmentCount(); ++s) {
      const double seg_m2 = masks.shareSum(s) * g.pixel_size_m * g.pixel_size_m;
      EXPECT_GT(seg_m2, 0.85 * geo.segments[s].length_m * w) << geo.segments[s].name;
      EXPECT_LT(seg_m2, 1.05 * geo.segments[s].length_m * w) << geo.segments[s].name;
    }
  }
}

TEST(StripMasks, WithPixelCentresEachSegmentLeaksOverItsOwnPixelsWhole) {
  const PixelGrid g = grid(256, 256);
  const StripMasks masks(geometry(), g, "test");
  EXPECT_EQ(masks.outline(), StripOutline::kPixelCentres);
  for (std::size_t s = 0; s < masks.segmentCount(); ++s) {
    EXPECT_EQ(masks.leakPixels(s), masks.segmentPixels(s)) << geometry().segments[s].name;
    ASSERT_EQ(masks.leakShares(s).size(), masks.segmentPixels(s).size());
    for (const double share : masks.leakShares(s)) ASSERT_EQ(share, 1.0);
    EXPECT_EQ(masks.shareSum(s), static_cast<double>(masks.segmentPixels(s).size()));
  }
}

TEST(StripMasks, SubpixelSharesHoldEveryPixelCentreOfTheStripsAndMore) {
  // A pixel whose centre lies in a strip has a share of it; the shares' outline adds the pixels
  // whose square only meets a strip.
  const PixelGrid g = grid(256, 256);
  const StripMasks centres(geometry(), g, "test");
  const StripMasks shares(geometry(), g, "test", StripOutline::kSubpixelShares);
  EXPECT_EQ(shares.outline(), StripOutline::kSubpixelShares);
  for (const std::uint32_t raster : centres.sealingPixels()) {
    ASSERT_GE(shares.sealingIndexOfPixel(raster), 0) << "pixel " << raster;
  }
  EXPECT_GT(shares.sealingPixels().size(), centres.sealingPixels().size());
}

TEST(StripMasks, MirroredGridGivesMirroredSegments) {
  // y -> -y maps chamber k to chamber N + 2 - k; the grid's rows map r -> H - 1 - r. (At
  // 200 px the radial strips at ±90° would have pixel centres exactly on their edges.)
  const PixelGrid g = grid(203, 203);
  const StripMasks masks(geometry(), g, "test");
  const int n = geometry().outer_count;
  auto mirrorSegment = [n](int s) {
    const int kind = s / n;
    const int i = s % n + 1;  // 1..N
    if (kind == 1) return n + (n - i) % n;  // radial i_i+1 <-> radial (N+1-i)_(N+2-i)
    return kind * n + (n + 1 - i) % n;              // chamber i <-> chamber N + 2 - i
  };
  std::size_t matched = 0, total = 0;
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      const int s = masks.segmentOfPixel(static_cast<std::size_t>(r) * g.width_px + c);
      const int m = masks.segmentOfPixel(static_cast<std::size_t>(g.height_px - 1 - r) * g.width_px + c);
      if (s < 0 && m < 0) continue;
      ++total;
      matched += s >= 0 && m >= 0 && mirrorSegment(s) == m ? 1 : 0;
    }
  }
  // Only pixels exactly on a strip's edge or equidistant from two centre lines may break
  // the symmetry (rounding, and the lower index wins a tie).
  EXPECT_GT(static_cast<double>(matched) / total, 0.995);
}

TEST(StripMasks, SealingOutsideTheViewIsAConfigErrorNamingTheRobot) {
  try {
    StripMasks masks(geometry(), grid(200, 200, 0.70), "robots/cromsci.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("robots/cromsci.yaml: sealing segment outer1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
  }
  // The height matters too: 0.8 m wide but only 0.6 m high.
  EXPECT_THROW(StripMasks(geometry(), PixelGrid{256, 192, 0.8 / 256}, "r"), ConfigError);
}

TEST(StripMasks, PixelsCoarserThanTheStripsAreAConfigError) {
  try {
    StripMasks masks(geometry(), grid(5, 5), "robots/cromsci.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("covers no pixel"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace climbsim::sealing::testing
