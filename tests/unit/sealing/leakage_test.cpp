// Leakage per segment (docs/design.md#sealing-and-leakage): flat wall, gentle and deep cracks
// against values computed without the model, monotonicity in the crack depth, which segments leak
// as a crack turns under the robot, and segment subsets (shards) giving the same numbers; with
// the strips' pixel centres and with their sub-pixel shares.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"

namespace climbsim::sealing::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::size_t segmentIndex(const std::string& name) {
  for (std::size_t s = 0; s < geometry().segments.size(); ++s) {
    if (geometry().segments[s].name == name) return s;
  }
  throw std::invalid_argument(name);
}

TEST(Leakage, FlatWallGivesTheBasicLeakageExactly) {
  for (const StripOutline outline : kOutlines) {
    for (const PixelGrid g : {grid(128, 128), grid(256, 256), grid(300, 280, 0.9)}) {
      const auto m = model(g, outline);
      for (const float height : {0.0f, 0.003f, -0.004f}) {  // within the travel: the strip follows
        const auto result = m.compute(flatWall(g, height));
        for (std::size_t s = 0; s < m.segmentCount(); ++s) {
          const double basic = geometry().segments[s].length_m * robot().sealing.basic_gap_m;
          EXPECT_EQ(result.segments[s].leak_area_m2, basic)
              << geometry().segments[s].name << " at " << height << ", " << outlineName(outline);
          EXPECT_EQ(result.segments[s].mean_gap_m, 0.0);
          EXPECT_EQ(result.segments[s].leak_area_m2, m.closedLeaks()[s].leak_area_m2);
        }
      }
    }
  }
}

TEST(Leakage, AFlatWallBeyondTheTravelLeaksTheExcessEverywhere) {
  const PixelGrid g = grid(128, 128);
  const auto m = model(g);
  const double travel = robot().sealing.travel_m;
  const float height = -0.008f;
  const auto result = m.compute(flatWall(g, height));
  for (std::size_t s = 0; s < m.segmentCount(); ++s) {
    const double gap = -travel - static_cast<double>(height);
    EXPECT_NEAR(result.segments[s].mean_gap_m, gap, 1e-15);
    EXPECT_NEAR(result.segments[s].leak_area_m2,
                geometry().segments[s].length_m * (robot().sealing.basic_gap_m + robot().sealing.kappa_L * gap), 1e-15);
  }
}

/// A crack across radial1_2 at its middle, running perpendicular to the wall, with walls of
/// `wall_slope` and a flat bottom `bottom_m` wide at `depth_m`; short enough to touch no
/// other strip.
Crack crackAcrossRadial12(double depth_m, double bottom_m, double wall_slope) {
  const double wall_rad = kPi / 6;  // between chambers 1 and 2
  const double r_mid = (geometry().centre_radius_m + geometry().ring_outer_radius_m) / 2;
  Crack c;
  c.x_m = r_mid * std::cos(wall_rad);
  c.y_m = r_mid * std::sin(wall_rad);
  c.angle_rad = wall_rad + kPi / 2;
  c.depth_m = depth_m;
  c.bottom_width_m = bottom_m;
  c.wall_slope = wall_slope;
  c.half_length_m = 0.04;
  return c;
}

TEST(Leakage, ACrackShallowerThanTheTravelWithWallsTheSealingCanFollowLeaksNothingExtra) {
  const double slope = robot().sealing.max_slope;
  const double depth = 0.8 * robot().sealing.travel_m;
  for (const int px : {128, 256, 512}) {
    const PixelGrid g = grid(px, px);
    const auto m = model(g);
    DepthGrid depth_image = flatWall(g);
    // Walls at half the slope the sealing can follow, a bottom three strip widths wide.
    addCrack(depth_image, crackAcrossRadial12(depth, 0.06, slope / 2));
    const auto result = m.compute(depth_image);
    const std::size_t radial = segmentIndex("radial1_2");
    double lowest = 0;
    for (const auto k : m.masks().segmentPixels(radial)) {
      lowest = std::min(lowest, static_cast<double>(depth_image.height_m[m.masks().sealingPixels()[k]]));
    }
    ASSERT_LT(lowest, -0.9 * depth) << "the crack must reach the strip";
    for (std::size_t s = 0; s < m.segmentCount(); ++s) {
      EXPECT_EQ(result.segments[s].leak_area_m2, m.closedLeaks()[s].leak_area_m2)
          << geometry().segments[s].name << " at " << px << " px";
    }
  }
}

TEST(Leakage, ACrackDeeperThanTheTravelLeaksItsExcessDepthOverItsCrossingWidth) {
  const double travel = robot().sealing.travel_m;
  const double slope = robot().sealing.max_slope;
  const double depth = 0.012, bottom = 0.02, wall_slope = 2.0 / 3.0 * slope;
  // Cross-section of the crack below the travel: excess e(u) = max(0, -travel - h(u)),
  // integral over the crossing = (D - T) b + (D - T)^2 / g  [m^2].
  const double excess_section_m2 = (depth - travel) * bottom + (depth - travel) * (depth - travel) / wall_slope;
  for (const auto& [outline, px] : {std::pair{StripOutline::kPixelCentres, 256}, std::pair{StripOutline::kPixelCentres, 512},
                                    std::pair{StripOutline::kPixelCentres, 1024}, std::pair{StripOutline::kSubpixelShares, 256},
                                    std::pair{StripOutline::kSubpixelShares, 512}, std::pair{StripOutline::kSubpixelShares, 1024}}) {
    const PixelGrid g = grid(px, px);
    const auto m = model(g, outline);
    DepthGrid depth_image = flatWall(g);
    addCrack(depth_image, crackAcrossRadial12(depth, bottom, wall_slope));
    const auto result = m.compute(depth_image);
    const std::size_t radial = segmentIndex("radial1_2");
    const auto& mine = m.masks().leakPixels(radial);
    const auto& shares = m.masks().leakShares(radial);
    // Without the adaptation: the walls are gentle, so only the travel limit opens a gap.
    double sum = 0;
    for (std::size_t n = 0; n < mine.size(); ++n) {
      sum += shares[n] * std::max(0.0, -travel - static_cast<double>(depth_image.height_m[m.masks().sealingPixels()[mine[n]]]));
    }
    const auto& leak = result.segments[radial];
    const double l = geometry().segments[radial].length_m;
    EXPECT_NEAR(leak.mean_gap_m, sum / m.masks().shareSum(radial), 1e-15);
    EXPECT_NEAR(leak.max_gap_m, depth - travel, 1e-9);
    // The extra leak area of the segment is the crossing's excess section, scaled by the
    // strip's length over its area (the formula's l_i / sum_j a_ij against the strip's w):
    const double strip_area_m2 = m.masks().shareSum(radial) * g.pixel_size_m * g.pixel_size_m;
    const double expected_extra_m2 = excess_section_m2 * geometry().strip_width_m * l / strip_area_m2;
    const double extra_m2 = leak.leak_area_m2 - l * robot().sealing.basic_gap_m;
    EXPECT_NEAR(extra_m2 / expected_extra_m2, 1.0, px >= 512 ? 0.02 : 0.05) << px << " px, " << outlineName(outline);
    for (std::size_t s = 0; s < m.segmentCount(); ++s) {
      if (s == radial) continue;
      EXPECT_EQ(result.segments[s].leak_area_m2, m.closedLeaks()[s].leak_area_m2) << geometry().segments[s].name;
    }
  }
}

TEST(Leakage, LeakageGrowsMonotonicallyWithCrackDepth) {
  const PixelGrid g = grid(256, 256);
  const auto m = model(g);
  std::vector<double> previous(m.segmentCount(), 0.0);
  double previous_total = 0.0;
  for (int mm = 0; mm <= 45; ++mm) {
    DepthGrid depth_image = flatWall(g);
    Crack crack;  // vertical walls, along x through the centre: crosses outer1, outer4, inner1, inner4
    crack.angle_rad = 0.1;
    crack.bottom_width_m = 0.015;
    crack.depth_m = mm * 1e-3;
    addCrack(depth_image, crack);
    clampToCamera(depth_image);
    const auto result = m.compute(depth_image);
    double total = 0;
    for (std::size_t s = 0; s < m.segmentCount(); ++s) {
      EXPECT_GE(result.segments[s].leak_area_m2, previous[s]) << geometry().segments[s].name << " at " << mm << " mm";
      previous[s] = result.segments[s].leak_area_m2;
      total += previous[s];
    }
    if (mm > 0) {
      EXPECT_GT(total, previous_total) << mm << " mm";
    }
    previous_total = total;
  }
}

/// Distance between the line through the origin along `angle_rad` and a polyline [m]
/// (0 if they cross).
double lineToPolyline_m(double angle_rad, const std::vector<RobotGeometry::Point>& line) {
  const double nx = -std::sin(angle_rad), ny = std::cos(angle_rad);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < line.size(); ++k) {
    const double d = line[k].x_m * nx + line[k].y_m * ny;
    best = std::min(best, std::abs(d));
    if (k > 0) {
      const double prev = line[k - 1].x_m * nx + line[k - 1].y_m * ny;
      if ((prev < 0) != (d < 0)) return 0.0;
    }
  }
  return best;
}

TEST(Leakage, TurningACrackUnderTheRobotChangesWhichSegmentsLeakAsTheGeometrySays) {
  const PixelGrid g = grid(256, 256);
  const auto m = model(g);
  const double half_crack = 0.005, half_strip = geometry().strip_width_m / 2, margin = 2 * g.pixel_size_m;
  std::vector<int> leaked(m.segmentCount(), 0), sealed(m.segmentCount(), 0);
  for (int deg = 0; deg < 360; deg += 5) {
    const double angle = deg * kPi / 180;
    DepthGrid depth_image = flatWall(g);
    Crack crack;
    crack.angle_rad = angle;
    crack.bottom_width_m = 2 * half_crack;
    crack.depth_m = 0.008;
    addCrack(depth_image, crack);
    const auto result = m.compute(depth_image);
    for (std::size_t s = 0; s < m.segmentCount(); ++s) {
      const double d = lineToPolyline_m(angle, geometry().segments[s].centreline_Robot);
      const auto& name = geometry().segments[s].name;
      const double basic = m.closedLeaks()[s].leak_area_m2;
      if (d < half_crack + half_strip - margin) {
        EXPECT_GT(result.segments[s].leak_area_m2, basic) << name << " at " << deg << " deg";
        ++leaked[s];
      } else if (d > half_crack + half_strip + margin) {
        EXPECT_EQ(result.segments[s].leak_area_m2, basic) << name << " at " << deg << " deg";
        ++sealed[s];
      }
    }
  }
  for (std::size_t s = 0; s < m.segmentCount(); ++s) {
    EXPECT_GT(leaked[s], 0) << geometry().segments[s].name << " never crossed";
    EXPECT_GT(sealed[s], 0) << geometry().segments[s].name << " never clear";
  }
}

TEST(Leakage, AnySubsetOfSegmentsGivesTheSameNumbersAsAllSegmentsBitForBit) {
  const PixelGrid g = grid(200, 200);
  for (const StripOutline outline : kOutlines) {
    const auto m = model(g, outline);
    for (std::uint64_t seed = 7; seed < 17; ++seed) {
      const DepthGrid depth = randomSurface(g, seed);
      const auto all = m.compute(depth);
      for (std::size_t shards = 2; shards <= 5; ++shards) {
        for (std::size_t shard = 0; shard < shards; ++shard) {
          std::vector<std::size_t> mine;
          for (std::size_t s = shard; s < m.segmentCount(); s += shards) mine.push_back(s);
          SealingResult part;
          m.compute(depth, mine, part);
          for (const std::size_t s : mine) {
            ASSERT_TRUE(sameBits(part.segments[s].leak_area_m2, all.segments[s].leak_area_m2))
                << "seed " << seed << ", " << outlineName(outline);
            ASSERT_TRUE(sameBits(part.segments[s].mean_gap_m, all.segments[s].mean_gap_m))
                << "seed " << seed << ", " << outlineName(outline);
          }
        }
      }
    }
  }
}

TEST(Leakage, TheStepsLeakageIsSegmentLeaksOnTheAdaptedSealingBitForBit) {
  // SealingModel::step sums each segment's gaps and its shares over no wall in one pass over
  // the doubles the adaptation kept; segmentLeak on the adaptation's heights, and the shares of
  // the image's own pixels at far, are the definitions: the same doubles, whole and sharded.
  const PixelGrid g = grid(200, 200);
  const double far_m = -0.05;
  for (const StripOutline outline : kOutlines) {
    const auto m = model(g, outline);
    const SealingAdapter adapter(m.masks(), m.neighbourhood());
    for (std::uint64_t seed = 21; seed < 27; ++seed) {
      DepthGrid depth = randomSurface(g, seed);
      // A third of the image sees no wall (far), as past the edge of a scene.
      for (int r = 0; r < g.height_px; ++r) {
        for (int c = 0; c < g.width_px / 3; ++c) depth.height_m[r * g.width_px + c] = static_cast<float>(far_m);
      }
      std::vector<double> sealing = adapter.adapt(depth.height_m);
      applyTravel(m.params(), sealing);
      for (const std::size_t shards : {std::size_t{1}, std::size_t{3}}) {
        for (std::size_t shard = 0; shard < shards; ++shard) {
          std::vector<std::size_t> mine;
          for (std::size_t s = shard; s < m.segmentCount(); s += shards) mine.push_back(s);
          SealingState state = m.initialState(mine);
          SealingInputs inputs;
          inputs.depth = &depth;
          inputs.far_m = far_m;
          const SealingOutputs out = m.step(state, inputs, 0, 0);
          for (const std::size_t s : mine) {
            SCOPED_TRACE(std::string(outlineName(outline)) + ", seed " + std::to_string(seed) + ", segment " +
                         m.params().segment_names[s]);
            const SegmentLeak want = segmentLeak(m.params(), m.masks(), s, depth.height_m, sealing);
            const SegmentLeak& got = out.leaks[s];
            EXPECT_TRUE(sameBits(got.leak_area_m2, want.leak_area_m2));
            EXPECT_TRUE(sameBits(got.mean_gap_m, want.mean_gap_m));
            EXPECT_TRUE(sameBits(got.max_gap_m, want.max_gap_m));
            EXPECT_EQ(got.over_travel_px, want.over_travel_px);
            EXPECT_EQ(got.pixels, want.pixels);
            double none = 0.0;
            const auto& pixels = m.masks().leakPixels(s);
            for (std::size_t n = 0; n < pixels.size(); ++n) {
              const float h = depth.height_m[m.masks().sealingPixels()[pixels[n]]];
              none += static_cast<double>(h) <= far_m + 1e-6 ? m.masks().leakShares(s)[n] : 0.0;
            }
            EXPECT_TRUE(sameBits(got.no_surface_share, none / m.masks().shareSum(s)));
          }
        }
      }
    }
  }
}

TEST(Leakage, ABadDepthImageIsRefusedWithItsReason) {
  const PixelGrid g = grid(128, 128);
  const auto m = model(g);
  DepthGrid wrong_size = flatWall(grid(64, 64));
  EXPECT_THROW(m.compute(wrong_size), std::invalid_argument);
  DepthGrid nan = flatWall(g);
  nan.height_m[5 * 128 + 7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(checkDepthGrid(nan, g), "pixel (row 5, col 7) height_m = nan (must be finite)");
  EXPECT_THROW(m.compute(nan), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::sealing::testing
