#include "pacing.hpp"

#include <gtest/gtest.h>

namespace climbsim::clock {
namespace {

using namespace std::chrono_literals;

TEST(Pacing, RealTimeFactorZeroNeverWaits) {
  const PacingAnchor anchor{WallClock::time_point{} + 7s, 10};
  EXPECT_EQ(pacedStart(anchor, 10'000'000, 5'000'000, 0.0), anchor.wall);
}

TEST(Pacing, RealTimeFactorOneMapsSimulatedToWallTime) {
  const PacingAnchor anchor{WallClock::time_point{} + 1s, 0};
  // step 1000 of 5 ms starts 5 s of simulated time after step 0
  EXPECT_EQ(pacedStart(anchor, 1000, 5'000'000, 1.0), anchor.wall + 5s);
}

TEST(Pacing, FactorScalesWallTimeInversely) {
  const PacingAnchor anchor{WallClock::time_point{}, 100};
  const auto at1 = pacedStart(anchor, 300, 1'000'000, 1.0) - anchor.wall;
  const auto at2 = pacedStart(anchor, 300, 1'000'000, 2.0) - anchor.wall;
  const auto at_half = pacedStart(anchor, 300, 1'000'000, 0.5) - anchor.wall;
  EXPECT_EQ(at1, 200ms);
  EXPECT_EQ(at2, 100ms);
  EXPECT_EQ(at_half, 400ms);
}

TEST(Pacing, CountsFromTheAnchorNotFromZero) {
  // After a pause the clock re-anchors; it must not race to catch up.
  const PacingAnchor anchor{WallClock::time_point{} + 60s, 500};
  EXPECT_EQ(pacedStart(anchor, 500, 5'000'000, 1.0), anchor.wall);
  EXPECT_EQ(pacedStart(anchor, 501, 5'000'000, 1.0), anchor.wall + 5ms);
}

TEST(Pacing, ExactOverLongRuns) {
  // 24 h of 1 ms steps at factor 1: no drift from rounding.
  const PacingAnchor anchor{WallClock::time_point{}, 0};
  EXPECT_EQ(pacedStart(anchor, 86'400'000, 1'000'000, 1.0) - anchor.wall, std::chrono::hours(24));
}

}  // namespace
}  // namespace climbsim::clock
