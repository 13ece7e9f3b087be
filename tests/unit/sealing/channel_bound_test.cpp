// The optional channel bound on the leakage (channel_bound.hpp) on synthetic cracks
// of known section: 10 mm wide, 40 mm deep, flat bottom, on a flat wall.

#include <gtest/gtest.h>

#include <cmath>

#include "sealing_surfaces.hpp"
#include "sealing_test_robot.hpp"

namespace climbsim::sealing::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kWidthM = 0.010;
constexpr double kDepthM = 0.040;

std::size_t segmentIndex(const std::string& name) {
  for (std::size_t s = 0; s < geometry().segments.size(); ++s) {
    if (geometry().segments[s].name == name) return s;
  }
  throw std::invalid_argument(name);
}

SealingModel boundedModel(const PixelGrid& g) {
  SealingParams p = sealingParamsFromRobot(robot(), geometry());
  p.channel_bound = true;
  return SealingModel(p, geometry(), g, robotFile());
}

/// radial1_2 runs from r = 0.15 to 0.36 m at 30 degrees.
constexpr double kRadial12Rad = kPi / 6.0;

TEST(ChannelBound, IsOffByDefault) { EXPECT_FALSE(sealingParamsFromRobot(robot(), geometry()).channel_bound); }

TEST(ChannelBound, TheRobotFileKeySwitchesItOn) {
  RobotDescription on = robot();
  on.sealing.channel_bound = true;  // sealing.channel_bound: true (robot_test.cpp reads the key)
  EXPECT_TRUE(sealingParamsFromRobot(on, geometry()).channel_bound);
}

TEST(ChannelBound, ACrackAcrossAStripKeepsItsChannelCrossSection) {
  const PixelGrid g = grid(1024, 1024);  // 0.8 mm pixels: 12 across the crack
  DepthGrid d = flatWall(g);
  // Across radial1_2 at r = 0.25 m, 6 cm long: it crosses that strip only.
  Crack crack;
  crack.x_m = 0.25 * std::cos(kRadial12Rad);
  crack.y_m = 0.25 * std::sin(kRadial12Rad);
  crack.angle_rad = kRadial12Rad + kPi / 2.0;
  crack.bottom_width_m = kWidthM;
  crack.depth_m = kDepthM;
  crack.half_length_m = 0.03;
  addCrack(d, crack);
  const std::size_t s = segmentIndex("radial1_2");
  const double plain = model(g).compute(d).segments[s].leak_area_m2;
  const double bounded = boundedModel(g).compute(d).segments[s].leak_area_m2;
  // The channel: 10 mm wide, 40 mm deep less what the sealing reaches into it (at most 5 mm).
  const double basic = geometry().segments[s].length_m * robot().sealing.basic_gap_m;
  EXPECT_GT(plain - basic, 0.85 * kWidthM * (kDepthM - 0.005));
  EXPECT_LT(plain - basic, 1.15 * kWidthM * kDepthM);
  // Crossing, the bound keeps the channel's cross-section.
  EXPECT_GT(bounded - basic, 0.85 * kWidthM * (kDepthM - 0.005));
  EXPECT_LE(bounded, plain);
}

TEST(ChannelBound, ACrackAlongAStripUnderItIsNotALeakAcrossIt) {
  const PixelGrid g = grid(256, 256);
  DepthGrid d = flatWall(g);
  // Along radial1_2's centre line, from r = 0.18 to 0.33 m: under the strip, crossing neither
  // of its edges (the chambers 1 and 2 on either side see no opening).
  Crack crack;
  crack.x_m = 0.255 * std::cos(kRadial12Rad);
  crack.y_m = 0.255 * std::sin(kRadial12Rad);
  crack.angle_rad = kRadial12Rad;
  crack.bottom_width_m = kWidthM;
  crack.depth_m = kDepthM;
  crack.half_length_m = 0.075;
  addCrack(d, crack);
  const std::size_t s = segmentIndex("radial1_2");
  const double basic = geometry().segments[s].length_m * robot().sealing.basic_gap_m;
  const double plain = model(g).compute(d).segments[s].leak_area_m2;
  const double bounded = boundedModel(g).compute(d).segments[s].leak_area_m2;
  // docs/design.md#sealing-and-leakage counts its whole length: about 15 cm x 38 mm spread over the
  // 2 cm strip.
  EXPECT_GT(plain - basic, 5.0 * kWidthM * (kDepthM - 0.005));
  // Bounded: the strip's edges touch the wall, nothing crosses it but the basic gap.
  EXPECT_NEAR(bounded, basic, 1e-9);
}

TEST(ChannelBound, AFlatWallIsUnchanged) {
  const PixelGrid g = grid(128, 128);
  const auto plain = model(g).compute(flatWall(g, -0.008f));
  const auto bounded = boundedModel(g).compute(flatWall(g, -0.008f));
  for (std::size_t s = 0; s < plain.segments.size(); ++s) {
    // 3 mm everywhere beyond the travel: both edges are open along the whole strip, by as
    // much as the strip: the bound does not bind.
    EXPECT_NEAR(bounded.segments[s].leak_area_m2, plain.segments[s].leak_area_m2, 1e-15) << geometry().segments[s].name;
  }
}

}  // namespace
}  // namespace climbsim::sealing::testing
