// Sharded sealing: each shard adapts only its region, and its segments get the
// whole sealing's doubles; N shards together adapt little more than the whole sealing once.
// Both outlines of the strips: their pixel centres and their sub-pixel shares.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <utility>

#include "climbsim/errors.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "leakage.hpp"
#include "climbsim/shard_tiles/shard_region.hpp"

namespace climbsim::sealing::testing {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Every own pixel's sealing height and every own segment's numbers of a shard equal the
/// whole sealing's, bit for bit.
void expectShardsEqualWhole(const SealingModel& m, const DepthGrid& depth, std::size_t n, const std::string& what) {
  const SealingResult whole = m.compute(depth);
  const auto parts = partitionSegments(m.masks(), n);
  for (std::size_t i = 0; i < n; ++i) {
    SealingResult part;
    m.compute(depth, parts[i], part);
    for (const std::size_t s : parts[i]) {
      for (const std::uint32_t k : m.masks().leakPixels(s)) {
        ASSERT_TRUE(sameBits(part.sealing_m[k], whole.sealing_m[k]))
            << what << ", shard " << i << "/" << n << ", segment " << s << ", sealing pixel " << k << ": "
            << part.sealing_m[k] << " vs " << whole.sealing_m[k];
      }
      const SegmentLeak& a = part.segments[s];
      const SegmentLeak& b = whole.segments[s];
      ASSERT_TRUE(sameBits(a.leak_area_m2, b.leak_area_m2) && sameBits(a.mean_gap_m, b.mean_gap_m) &&
                  sameBits(a.max_gap_m, b.max_gap_m) && a.over_travel_px == b.over_travel_px)
          << what << ", shard " << i << "/" << n << ", segment " << s;
    }
  }
}

TEST(ShardPartition, EveryShardGetsItsOwnRunOfSegmentsWithAboutEqualPixelCounts) {
  const auto m = model(grid(256, 256));
  for (std::size_t n = 1; n <= 6; ++n) {
    const auto parts = partitionSegments(m.masks(), n);
    ASSERT_EQ(parts.size(), n);
    std::set<std::size_t> seen;
    std::size_t smallest = std::numeric_limits<std::size_t>::max();
    std::size_t largest = 0;
    for (const auto& part : parts) {
      ASSERT_FALSE(part.empty());
      std::size_t pixels = 0;
      for (const std::size_t s : part) {
        EXPECT_TRUE(seen.insert(s).second) << "segment " << s << " in two shards of " << n;
        pixels += m.masks().segmentPixels(s).size();
      }
      smallest = std::min(smallest, pixels);
      largest = std::max(largest, pixels);
    }
    EXPECT_EQ(seen.size(), m.segmentCount()) << n << " shards";
    EXPECT_LE(static_cast<double>(largest), 1.6 * static_cast<double>(smallest)) << n << " shards";
  }
  try {
    partitionSegments(m.masks(), 19);
    FAIL() << "19 shards of 18 segments";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("only 18 sealing segments"), std::string::npos) << e.what();
  }
}

TEST(ShardRegion, PixelsComeInBandsOfDistanceFromTheOwnSegmentsAlongTheStrips) {
  for (const StripOutline outline : kOutlines) {
    SCOPED_TRACE(outlineName(outline));
    const auto m = model(grid(256, 256), outline);
    const auto parts = partitionSegments(m.masks(), 2);
    const ShardRegion region(m.masks(), m.neighbourhood(), parts[0], m.grid().pixel_size_m);
    // Own: every pixel the shard's segments' leakage reads (a pixel at a junction once).
    std::set<std::uint32_t> own_pixels;
    for (const std::size_t s : parts[0]) own_pixels.insert(m.masks().leakPixels(s).begin(), m.masks().leakPixels(s).end());
    const std::size_t own = own_pixels.size();
    EXPECT_EQ(region.ownCount(), own);
    const auto& d = region.distance_m();
    const double band_m = ShardRegion::kBandPixels * m.grid().pixel_size_m;
    // Every own pixel (dist 0) lies in the first band, which comes first.
    EXPECT_GE(region.firstBandCount(), own);
    for (std::size_t i = 0; i < region.firstBandCount(); ++i) EXPECT_LT(d[i], band_m);
    for (std::size_t i = region.firstBandCount(); i < d.size(); ++i) ASSERT_GE(d[i], band_m);
    // Bands ascend; a prefix of countWithin(r) holds every pixel nearer than r, and no more than
    // one band beyond it.
    for (std::size_t i = 1; i < d.size(); ++i) ASSERT_LE(std::floor(d[i - 1] / band_m), std::floor(d[i] / band_m));
    for (const double r : {0.001, 0.02, 0.05, 0.11, 0.3}) {
      const std::size_t n = region.countWithin(r);
      for (std::size_t i = n; i < d.size(); ++i) ASSERT_GE(d[i], r) << "reach " << r;
      for (std::size_t i = 0; i < n; ++i) ASSERT_LT(d[i], r + band_m) << "reach " << r;
    }
    // The sealing is one connected piece: every pixel is somewhere in the region's order.
    EXPECT_EQ(d.size(), m.masks().sealingPixels().size());
    // The farthest pixel is at least a quarter of the outer circumference away along the strips.
    EXPECT_GT(*std::max_element(d.begin(), d.end()), 0.25 * 3.14159 * 0.72 * 0.5);
  }
}

TEST(ShardRegion, OneToFourShardsGiveTheWholeSealingsNumbersBitForBitOnRandomSurfaces) {
  for (const auto& [outline, px] : {std::pair{StripOutline::kPixelCentres, 96}, std::pair{StripOutline::kPixelCentres, 256},
                                    std::pair{StripOutline::kSubpixelShares, 96}, std::pair{StripOutline::kSubpixelShares, 256}}) {
    SCOPED_TRACE(outlineName(outline));
    const auto m = model(grid(px, px), outline);
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
      DepthGrid depth = randomSurface(m.grid(), seed);
      depth.upper_bound_m = 0.05;
      for (std::size_t n = 1; n <= 4; ++n) {
        expectShardsEqualWhole(m, depth, n, std::to_string(px) + " px, seed " + std::to_string(seed));
      }
      depth.upper_bound_m = std::numeric_limits<double>::infinity();
      expectShardsEqualWhole(m, depth, 3, std::to_string(px) + " px, seed " + std::to_string(seed) + ", near unknown");
    }
  }
}

TEST(ShardRegion, AHighPointFarAlongTheStripRaisesTheShardsPixelsAsInTheWholeSealing) {
  // A wall 20 mm below the strips (beyond the 5 mm travel: gaps everywhere) with one tall
  // point at the camera's near plane on the sealing 5..17 cm along the strips from a shard's
  // own pixels: its influence (0.05 - 0.3 d) still lifts the own pixels above -travel, so a
  // region that stops short of it gives other doubles.
  for (const StripOutline outline : kOutlines) {
    SCOPED_TRACE(outlineName(outline));
    const auto m = model(grid(256, 256), outline);
    const auto parts = partitionSegments(m.masks(), 4);
    const ShardRegion region(m.masks(), m.neighbourhood(), parts[0], m.grid().pixel_size_m);
    int tried = 0;
    for (const double reach_m : {0.05, 0.09, 0.13, 0.17}) {
      // The pixel nearest to reach_m beyond it.
      const auto& d = region.distance_m();
      std::size_t i = d.size();
      for (std::size_t j = 0; j < d.size(); ++j) {
        if (d[j] >= reach_m && (i == d.size() || d[j] < d[i])) i = j;
      }
      ASSERT_LT(i, d.size());
      DepthGrid depth = flatWall(m.grid(), -0.02f);
      depth.upper_bound_m = 0.05;
      depth.height_m[m.masks().sealingPixels()[region.sealingIndices()[i]]] = 0.05f;
      const SealingResult whole = m.compute(depth);
      // The point does lift the shard's nearest pixels.
      double highest = -1.0;
      for (const std::size_t s : parts[0]) {
        for (const std::uint32_t k : m.masks().leakPixels(s)) highest = std::max(highest, whole.sealing_m[k]);
      }
      EXPECT_GT(highest, -0.005) << "point at " << reach_m << " m";
      expectShardsEqualWhole(m, depth, 4, "point at " + std::to_string(reach_m) + " m");
      ++tried;
    }
    EXPECT_EQ(tried, 4);
  }
}

TEST(ShardRegion, OnAFlatWallTheHaloReachesOnlyAsFarAsAPeakCanStillLiftTheCut) {
  // A flat wall at 0 and one peak of U = 20 mm on another shard's pixel at path distance D from
  // the shard's own pixels: it lifts the own pixels at the cut above the wall (and above the
  // -5 mm travel floor) exactly while U - k D > 0, i.e. D < U / k = 67 mm. The region needs no
  // more than that (plus a pixel and the margin), not the (U + travel) / k = 83 mm that a wall
  // below the travel would need, and it still gives the whole sealing's doubles for peaks
  // just inside that reach.
  // 1024 px: bands of 6.25 mm, fine enough to tell 67 from 83 mm and to miss a peak at 66 mm
  // if the halo were 10 % short.
  const auto m = model(grid(1024, 1024));
  const auto parts = partitionSegments(m.masks(), 2);
  const ShardRegion region(m.masks(), m.neighbourhood(), parts[0], m.grid().pixel_size_m);
  const double upper_m = 0.02;
  const double k = m.params().max_slope;
  const double s = m.grid().pixel_size_m;
  const std::size_t wider = region.countWithin((upper_m + m.params().travel_m) / k + region.margin_m());
  const auto& d = region.distance_m();
  for (const double fraction : {0.5, 0.8, 0.95, 0.99, 0.999}) {
    const double reach_m = fraction * upper_m / k;
    std::size_t i = d.size();
    for (std::size_t j = 0; j < d.size(); ++j) {
      if (d[j] <= reach_m && (i == d.size() || d[j] > d[i])) i = j;
    }
    ASSERT_LT(i, d.size());
    DepthGrid depth = flatWall(m.grid(), 0.0f);
    depth.upper_bound_m = upper_m;
    depth.height_m[m.masks().sealingPixels()[region.sealingIndices()[i]]] = static_cast<float>(upper_m);
    const SealingResult whole = m.compute(depth);
    double highest = -1.0;
    for (const std::size_t seg : parts[0]) {
      for (const std::uint32_t p : m.masks().leakPixels(seg)) highest = std::max(highest, whole.sealing_m[p]);
    }
    EXPECT_GT(highest, 0.0) << "a peak " << d[i] << " m away lifts the cut";
    SealingResult part;
    m.compute(depth, parts[0], part);
    EXPECT_LE(static_cast<double>(part.adapted_px), static_cast<double>(region.countWithin(upper_m / k + s + region.margin_m())))
        << "peak " << d[i] << " m away";
    EXPECT_LT(part.adapted_px, wider) << "peak " << d[i] << " m away";
    expectShardsEqualWhole(m, depth, 2, "flat wall, peak " + std::to_string(d[i]) + " m away");
  }
}

TEST(ShardRegion, AWallBelowTheTravelNeedsTheFullHaloAndGetsIt) {
  // The same peak on a wall 20 mm down: the own pixels rest on the travel floor (-5 mm), and
  // the peak lifts them while U - k D > -travel, i.e. D < (U + travel) / k: the region must
  // reach that far, and the own pixels' floors do not shrink it.
  const auto m = model(grid(256, 256));
  const auto parts = partitionSegments(m.masks(), 2);
  const ShardRegion region(m.masks(), m.neighbourhood(), parts[0], m.grid().pixel_size_m);
  const double upper_m = 0.02;
  const double full_m = (upper_m + m.params().travel_m) / m.params().max_slope;
  DepthGrid depth = flatWall(m.grid(), -0.02f);
  depth.upper_bound_m = upper_m;
  EXPECT_GE(region.activeCount(m.params(), depth.height_m, upper_m), region.countWithin(full_m));
  const auto& d = region.distance_m();
  std::size_t i = d.size();
  for (std::size_t j = 0; j < d.size(); ++j) {
    if (d[j] <= 0.98 * full_m && (i == d.size() || d[j] > d[i])) i = j;
  }
  ASSERT_LT(i, d.size());
  depth.height_m[m.masks().sealingPixels()[region.sealingIndices()[i]]] = static_cast<float>(upper_m);
  const SealingResult whole = m.compute(depth);
  double highest = -1.0;
  for (const std::size_t seg : parts[0]) {
    for (const std::uint32_t p : m.masks().leakPixels(seg)) highest = std::max(highest, whole.sealing_m[p]);
  }
  EXPECT_GT(highest, -m.params().travel_m);
  expectShardsEqualWhole(m, depth, 2, "wall below the travel, peak " + std::to_string(d[i]) + " m away");
}

TEST(ShardRegion, NShardsTogetherAdaptLittleMoreThanTheWholeSealingOnAWallWithCracks) {
  // Rough concrete (±1 mm) with two deep cracks, as under the robot on the pylon.
  const auto m = model(grid(256, 256));
  std::mt19937_64 rng(7);
  DepthGrid depth = flatWall(m.grid());
  addRoughness(depth, rng, 0.001, 0.02, 0.0002);
  for (const double y_m : {-0.1, 0.2}) {
    Crack c;
    c.y_m = y_m;
    c.bottom_width_m = 0.01;
    c.depth_m = 0.03;
    addCrack(depth, c);
  }
  clampToCamera(depth);
  // As the service does: the image's highest pixel bounds the regions.
  depth.upper_bound_m = *std::max_element(depth.height_m.begin(), depth.height_m.end());
  const std::size_t whole = m.masks().sealingPixels().size();
  for (std::size_t n = 2; n <= 4; ++n) {
    std::size_t adapted = 0;
    for (const auto& part : partitionSegments(m.masks(), n)) {
      SealingResult r;
      m.compute(depth, part, r);
      adapted += r.adapted_px;
    }
    // Each cut between shards adds a halo of about (h_max + travel) / slope plus a margin and a
    // band of the region's order at both sides: a few per cent of the sealing per cut here.
    EXPECT_LT(static_cast<double>(adapted), (1.0 + 0.075 * n) * static_cast<double>(whole)) << n << " shards adapt " << adapted
                                                                                << " of " << whole << " pixels";
    expectShardsEqualWhole(m, depth, n, "cracked wall");
  }
}

TEST(ShardRegion, EachShardOfAServiceEqualsTheOracleChainFrameAfterFrameAsItsRegionGrowsAndShrinks) {
  // The production path (adaptation along runs in place, the travel limit as its floor, one
  // leakage pass) against the paper's loop, applyTravel and segmentLeak, for the whole sealing
  // and every shard of 2..4 (every other frame with support heights), each with one result reused over frames whose height bounds make
  // its region grow and shrink (the pixels that leave the region must not leak into the next
  // frame). Cracks and holes deeper than the travel: the floor holds pixels up.
  for (const StripOutline outline : kOutlines) {
    SCOPED_TRACE(outlineName(outline));
    const auto m = model(grid(96, 96), outline);
    for (std::size_t n = 1; n <= 4; ++n) {
      const auto parts = partitionSegments(m.masks(), n);
      std::vector<SealingResult> results(n);
      for (std::uint64_t seed = 21; seed <= 32; ++seed) {
        DepthGrid depth = randomSurface(m.grid(), seed);
        // Every other frame with support heights (sub-pixel leakage's edge pixels).
        if (seed % 2 == 1) addSupports(depth, seed);
        double highest = *std::max_element(depth.height_m.begin(), depth.height_m.end());
        for (const float v : depth.supports.height_m) highest = std::max(highest, static_cast<double>(v));
        depth.upper_bound_m = seed % 3 == 0 ? std::numeric_limits<double>::infinity()
                                            : highest + (seed % 3 == 1 ? 0.0 : 0.06);
        auto oracle = adaptNaive(m.masks(), m.neighbourhood(), depth.height_m, nullptr, &depth.supports);
        applyTravel(m.params(), oracle);
        for (std::size_t i = 0; i < n; ++i) {
          m.compute(depth, parts[i], results[i]);
          for (const std::size_t s : parts[i]) {
            for (const std::uint32_t k : m.masks().leakPixels(s)) {
              ASSERT_TRUE(sameBits(results[i].sealing_m[k], oracle[k]))
                  << "seed " << seed << ", shard " << i << "/" << n << ", sealing pixel " << k << ": "
                  << results[i].sealing_m[k] << " vs " << oracle[k];
            }
            const SegmentLeak want = segmentLeak(m.params(), m.masks(), s, depth.height_m, oracle);
            const SegmentLeak& got = results[i].segments[s];
            ASSERT_TRUE(sameBits(got.leak_area_m2, want.leak_area_m2) && sameBits(got.mean_gap_m, want.mean_gap_m) &&
                        sameBits(got.max_gap_m, want.max_gap_m) && got.over_travel_px == want.over_travel_px &&
                        got.pixels == want.pixels)
                << "seed " << seed << ", shard " << i << "/" << n << ", segment " << s;
          }
          // Outside its region a shard's result holds NaN, never a stale height.
          std::size_t defined = 0;
          for (const double h : results[i].sealing_m) defined += std::isnan(h) ? 0 : 1;
          EXPECT_EQ(defined, results[i].adapted_px) << "seed " << seed << ", shard " << i << "/" << n;
        }
      }
    }
  }
}

}  // namespace
}  // namespace climbsim::sealing::testing
