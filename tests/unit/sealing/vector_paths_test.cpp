// The sealing's passes over its pixels run in AVX registers where the CPU has AVX, else in SSE2
// registers (cpu_avx.hpp): both paths give the same doubles, flags and messages. On a CPU
// without AVX both runs take the SSE2 path and the comparison holds trivially.

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "cpu_avx.hpp"
#include "sealing_model.hpp"
#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"
#include "sealing_translate.hpp"

namespace climbsim::sealing::testing {
namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Runs `work` with the AVX passes allowed or not (where they are compiled), then allows them.
template <class Work>
auto withAvx(bool allowed, Work&& work) {
#if defined(CLIMBSIM_SEALING_AVX)
  avxPassesAllowed() = allowed;
#endif
  auto result = work();
#if defined(CLIMBSIM_SEALING_AVX)
  avxPassesAllowed() = true;
#endif
  return result;
}

/// A random surface with supports, its left fifth at the camera's far limit (no wall) and a
/// bump 8 mm high (over the 5 mm travel) in its middle: every branch of the leakage's passes.
DepthGrid testFrame(const PixelGrid& g, std::uint64_t seed) {
  DepthGrid depth = randomSurface(g, seed);
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      float& h = depth.height_m[static_cast<std::size_t>(r) * g.width_px + c];
      if (c < g.width_px / 5) h = -0.05f;
      if (r > g.height_px / 3 && r < g.height_px / 2 && c > g.width_px / 2) h = 0.008f;
    }
  }
  addSupports(depth, seed);
  // Each support 1 mm above its pixel (the bump and the far fifth changed them).
  for (std::size_t i = 0; i < depth.supports.raster.size(); ++i) {
    depth.supports.height_m[i] = std::max(depth.height_m[depth.supports.raster[i]], -0.049f) + 0.001f;
  }
  return depth;
}

TEST(VectorPaths, TheStepsSealingAndLeakageAreTheSameDoublesOnBothPaths) {
  std::size_t over_travel = 0;
  double no_surface = 0.0;
  for (const StripOutline outline : kOutlines) {
    for (const PixelGrid& g : {grid(256, 256), PixelGrid{203, 197, 0.8 / 203}}) {
      const auto m = model(g, outline);
      for (std::uint64_t seed = 40; seed < 44; ++seed) {
        const DepthGrid depth = testFrame(g, seed);
        SealingInputs inputs;
        inputs.depth = &depth;
        inputs.far_m = -0.05;
        const auto run = [&] {
          std::vector<std::size_t> all(m.segmentCount());
          for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
          SealingState state = m.initialState(all);
          m.step(state, inputs, 0, 0);
          return state;
        };
        const SealingState avx = withAvx(true, run);
        const SealingState sse2 = withAvx(false, run);
        SCOPED_TRACE(std::string(outlineName(outline)) + ", seed " + std::to_string(seed));
        ASSERT_EQ(avx.last.sealing_m.size(), sse2.last.sealing_m.size());
        for (std::size_t k = 0; k < avx.last.sealing_m.size(); ++k) {
          ASSERT_TRUE(sameBits(avx.last.sealing_m[k], sse2.last.sealing_m[k])) << "sealing pixel " << k;
        }
        for (std::size_t s = 0; s < m.segmentCount(); ++s) {
          EXPECT_TRUE(sameBits(avx.leaks[s].leak_area_m2, sse2.leaks[s].leak_area_m2)) << s;
          EXPECT_TRUE(sameBits(avx.leaks[s].mean_gap_m, sse2.leaks[s].mean_gap_m)) << s;
          EXPECT_TRUE(sameBits(avx.leaks[s].max_gap_m, sse2.leaks[s].max_gap_m)) << s;
          EXPECT_TRUE(sameBits(avx.leaks[s].no_surface_share, sse2.leaks[s].no_surface_share)) << s;
          EXPECT_EQ(avx.leaks[s].over_travel_px, sse2.leaks[s].over_travel_px) << s;
          over_travel += avx.leaks[s].over_travel_px;
          no_surface += avx.leaks[s].no_surface_share;
        }
      }
    }
  }
  // The frames must reach the counts over the travel and the shares over no wall.
  EXPECT_GT(over_travel, 0u);
  EXPECT_GT(no_surface, 0.0);
}

TEST(VectorPaths, TheHeightCheckNamesTheSamePixelAndFindsTheSameHighestOnBothPaths) {
  // 203 x 197 px: no multiple of 32 or 16 values, so both paths end with values one by one.
  const PixelGrid g{203, 197, 0.8 / 203};
  const climbsim::DepthImage clean = depthImageToIdl(flatWall(g, -0.01f), -0.05, 0.05);
  for (std::size_t at = 0; at < g.pixelCount(); at += 997) {
    for (const float v : {0.03f, 0.06f, -0.2f}) {
      climbsim::DepthImage sample = clean;
      sample.height_m()[at] = v;
      const auto check = [&] {
        float highest = 0.0f;
        const std::string why = checkDepthImage(sample, g, &highest);
        return std::pair{why, highest};
      };
      const auto avx = withAvx(true, check);
      const auto sse2 = withAvx(false, check);
      EXPECT_EQ(avx.first, sse2.first) << at << " " << v;
      EXPECT_EQ(avx.first.empty(), v == 0.03f) << at << " " << v;
      if (avx.first.empty()) {
        EXPECT_EQ(avx.second, sse2.second) << at;
      }
    }
  }
}

}  // namespace
}  // namespace climbsim::sealing::testing
