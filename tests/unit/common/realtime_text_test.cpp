// The real-time factor in log lines: digits a short run's small factor needs, and "n/a" where
// the wall time is below what can be measured.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "climbsim/realtime_text.hpp"

namespace climbsim {
namespace {

TEST(RealtimeText, SmallFactorsKeepTheirDigits) {
  EXPECT_EQ(realtimeText(0.005, 0.3), "0.017x real time") << "a two-step run, not 0.0x";
  EXPECT_EQ(realtimeText(0.0004), "0.0004x real time");
  EXPECT_EQ(realtimeText(0.5), "0.5x real time");
  EXPECT_EQ(realtimeText(3.42), "3.4x real time");
  EXPECT_EQ(realtimeText(23.6), "24x real time");
}

TEST(RealtimeText, WallTimeBelowResolutionOrNothingSimulatedIsNotAFigure) {
  EXPECT_EQ(realtimeText(0.005, 0.0), "n/a real time (0 ms wall)");
  EXPECT_EQ(realtimeText(0.005, 2e-4), "n/a real time (0.2 ms wall)");
  EXPECT_EQ(realtimeText(0.0, 0.5), "n/a real time (nothing simulated)");
  EXPECT_EQ(realtimeText(1.0, NAN), "n/a real time (0 ms wall)");
  EXPECT_EQ(realtimeText(0.0), "n/a real time");
  EXPECT_EQ(realtimeText(INFINITY), "n/a real time");
  EXPECT_EQ(realtimeText(2.0, 1e-3), "2000x real time") << "at the resolution: measured";
}

}  // namespace
}  // namespace climbsim
