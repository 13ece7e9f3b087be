// Body command -> wheel targets: kinematics, flipping, saturation, garbage detection.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "drive_command.hpp"
#include "setpoint_shaper.hpp"

namespace climbsim::drive {
namespace {

constexpr double kPi = 3.14159265358979323846;

DriveParams threeWheels() {
  DriveParams p;
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * kPi * i / 3.0;
    p.wheels.push_back({0.26 * std::cos(a), 0.26 * std::sin(a)});
  }
  return p;
}

TEST(DriveCommand, TranslationSteersEveryWheelAlongTheVelocity) {
  const auto p = threeWheels();
  DriveCommand c;
  c.vx_mps = 0.03;
  c.vy_mps = 0.04;
  const auto t = wheelTargets(p, c, std::vector<WheelSetpoint>(3));
  for (const auto& w : t) {
    EXPECT_NEAR(w.steering_rad, std::atan2(0.04, 0.03), 1e-12);
    EXPECT_NEAR(w.wheel_speed_radps * p.wheels[0].radius_m, 0.05, 1e-12);
  }
}

TEST(DriveCommand, RotationMakesEveryContactMoveTangentially) {
  const auto p = threeWheels();
  DriveCommand c;
  c.wz_radps = 0.2;
  const auto t = wheelTargets(p, c, std::vector<WheelSetpoint>(3));
  for (std::size_t i = 0; i < 3; ++i) {
    // Rolling direction times signed speed must equal wz x p_i.
    const double vx = std::cos(t[i].steering_rad) * t[i].wheel_speed_radps * p.wheels[0].radius_m;
    const double vy = std::sin(t[i].steering_rad) * t[i].wheel_speed_radps * p.wheels[0].radius_m;
    EXPECT_NEAR(vx, -0.2 * p.wheels[i].y_m, 1e-12);
    EXPECT_NEAR(vy, 0.2 * p.wheels[i].x_m, 1e-12);
    EXPECT_LE(std::fabs(t[i].steering_rad), kPi / 2 + 1e-12);
  }
}

TEST(DriveCommand, AWheelFlipsItsDirectionRatherThanSteeringMoreThan90Degrees) {
  const auto p = threeWheels();
  DriveCommand c;
  c.vx_mps = 0.05;
  auto t = wheelTargets(p, c, std::vector<WheelSetpoint>(3));
  c.vx_mps = -0.05;  // reverse: the same heading, negative speed
  t = wheelTargets(p, c, t);
  EXPECT_NEAR(t[0].steering_rad, 0.0, 1e-12);
  EXPECT_LT(t[0].wheel_speed_radps, 0.0);
  c.vx_mps = 0.0;
  c.vy_mps = -0.05;  // 90 degrees away from either: no more than 90 degrees of steering
  const auto u = wheelTargets(p, c, t);
  EXPECT_LE(std::fabs(u[0].steering_rad - t[0].steering_rad), kPi / 2 + 1e-12);
  EXPECT_NEAR(std::sin(u[0].steering_rad) * u[0].wheel_speed_radps * p.wheels[0].radius_m, -0.05, 1e-12);
}

TEST(DriveCommand, StandstillKeepsTheSteeringAndFastCommandsAreScaledAsAWhole) {
  const auto p = threeWheels();
  std::vector<WheelSetpoint> prev(3, WheelSetpoint{0.7, 1.0});
  const auto still = wheelTargets(p, DriveCommand{}, prev);
  for (const auto& w : still) {
    EXPECT_EQ(w.steering_rad, 0.7);
    EXPECT_EQ(w.wheel_speed_radps, 0.0);
  }
  DriveCommand c;
  c.vx_mps = 0.3;  // three times the limit
  c.wz_radps = 0.3;
  const auto t = wheelTargets(p, c, prev);
  double fastest = 0.0;
  for (const auto& w : t) fastest = std::max(fastest, std::fabs(w.wheel_speed_radps) * p.wheels[0].radius_m);
  EXPECT_NEAR(fastest, p.max_speed_mps, 1e-12);
}

TEST(DriveCommand, GarbageIsRecognisedAndNamed) {
  const auto p = threeWheels();
  DriveCommand c;
  c.vx_mps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(checkCommand(p, c).find("vx_mps"), std::string::npos);
  c.vx_mps = 50.0;
  EXPECT_NE(checkCommand(p, c), "");
  c.vx_mps = 0.5;  // above the limit but not absurd: saturated later
  EXPECT_EQ(checkCommand(p, c), "");
  DriveCommand w;
  w.steering_rad = {0.0, 0.0};
  w.wheel_speed_radps = {0.0, 0.0};
  EXPECT_NE(checkCommand(p, w).find("3 wheels"), std::string::npos);
  w.steering_rad = {0.0, 0.0, std::numeric_limits<double>::infinity()};
  w.wheel_speed_radps = {0.0, 0.0, 0.0};
  EXPECT_NE(checkCommand(p, w).find("steering_rad[2]"), std::string::npos);
}

TEST(SetpointShaper, SteeringFollowsAfterTheDeadTimeAtTheRateLimit) {
  const double h = 0.001;
  SetpointShaper shaper(1, 20, kPi / 2);
  const std::vector<WheelSetpoint> target{{kPi / 2, 2.0}};
  for (int k = 0; k < 20; ++k) {
    shaper.advance(target, h);
    EXPECT_EQ(shaper.references()[0].steering_rad, 0.0) << "moved inside the dead time at substep " << k;
  }
  double last = 0.0;
  for (int k = 0; k < 1000; ++k) {
    shaper.advance(target, h);
    const auto& r = shaper.references()[0];
    EXPECT_LE(r.steering_rad - last, kPi / 2 * h + 1e-15);
    // No rolling until the wheel is within the alignment window of its heading.
    if (kPi / 2 - r.steering_rad >= SetpointShaper::kAlignmentWindowRad) {
      EXPECT_EQ(r.wheel_speed_radps, 0.0);
    }
    last = r.steering_rad;
  }
  EXPECT_NEAR(last, kPi / 2, 1e-9);  // 90 degrees at 90 degrees/s: done after one second
  EXPECT_NEAR(shaper.references()[0].wheel_speed_radps, 2.0, 1e-9);
}

}  // namespace
}  // namespace climbsim::drive
