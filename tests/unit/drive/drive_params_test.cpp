// Drive parameters from the robot file: derived values and bad robots.

#include <gtest/gtest.h>

#include <cmath>

#include "climbsim/errors.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

RobotDescription cromsci() { return loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml"); }

/// The ConfigError message of driveParamsFromRobot for `robot`, or "" if it did not throw.
std::string errorOf(const RobotDescription& robot) {
  try {
    RobotDescription copy = robot;
    // Geometry is derived from a validated description; a bad one must be caught first.
    driveParamsFromRobot(copy, RobotGeometry{});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return {};
}

TEST(DriveParams, TheDefaultRobotGivesThreeWheelsAtItsMountRadius) {
  const auto robot = cromsci();
  const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  ASSERT_EQ(p.wheels.size(), 3u);
  for (const auto& w : p.wheels) EXPECT_NEAR(std::hypot(w.x_m, w.y_m), robot.wheels[0].mount_radius_m, 1e-12);
  EXPECT_EQ(p.mass_kg, robot.body.mass_kg);
  for (const auto& w : p.wheels) {
    EXPECT_EQ(w.kind, WheelKind::kSteerable);
    EXPECT_EQ(w.friction_coefficient, robot.wheels[0].friction_coefficient);
    EXPECT_EQ(w.relaxation_length_m, w.radius_m);
    EXPECT_EQ(w.trail_m, 0.0);
  }
  // The wheel torque limit lets each wheel use its share of the desired downforce's friction.
  EXPECT_NEAR(p.wheel_servo.torque_max_nm * 3.0 / p.wheels[0].radius_m,
              robot.wheels[0].friction_coefficient * robot.adhesion.desired_downforce_n, 1e-9);
  EXPECT_EQ(checkDriveParams(p), "");
}

TEST(DriveParams, NonPhysicalRobotsAreRejectedNamingTheKey) {
  auto robot = cromsci();
  robot.body.mass_kg = 0.0;
  EXPECT_NE(errorOf(robot).find("body.mass_kg"), std::string::npos) << errorOf(robot);
  robot = cromsci();
  robot.wheels[0].friction_coefficient = -0.5;
  EXPECT_NE(errorOf(robot).find("wheels[1].friction_coefficient"), std::string::npos) << errorOf(robot);
  robot = cromsci();
  robot.wheels[1].mount_radius_m = 0.5;  // beyond the 0.40 m body
  EXPECT_NE(errorOf(robot).find("wheels[2].mount_radius_m"), std::string::npos) << errorOf(robot);
}

TEST(DriveParams, EachWheelKeepsItsOwnKindRadiusAndFriction) {
  auto robot = cromsci();
  robot.wheels[2].kind = RobotDescription::WheelKind::kCaster;
  robot.wheels[1].radius_m = 0.04;
  robot.wheels[0].friction_coefficient = 0.5;
  const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  EXPECT_EQ(p.wheels[2].kind, WheelKind::kCaster);
  EXPECT_EQ(p.wheels[2].trail_m, robot.wheels[2].radius_m);
  EXPECT_EQ(p.wheels[1].radius_m, 0.04);
  EXPECT_EQ(p.wheels[1].relaxation_length_m, 0.04);
  EXPECT_EQ(p.wheels[0].friction_coefficient, 0.5);
  // 1 mm penetration of the smallest wheel under an equal share of the desired downforce.
  const double share = robot.adhesion.desired_downforce_n / 3.0;
  EXPECT_NEAR((4.0 / 3.0) * p.contact.hertz_modulus_pa * std::sqrt(0.04) * std::pow(1e-3, 1.5), share, 1e-9 * share);
  // The torque limit: the largest traction mu share r_w of a driven wheel (wheel 1: 0.5 x
  // 0.05 m, wheel 2: 0.7 x 0.04 m; wheel 3, a caster, is not driven).
  EXPECT_NEAR(p.wheel_servo.torque_max_nm, 0.7 * 0.04 * share, 1e-12);
}

TEST(DriveParams, ARobotOfCastersOnlyIsRefusedByName) {
  auto robot = cromsci();
  for (auto& w : robot.wheels) w.kind = RobotDescription::WheelKind::kCaster;
  EXPECT_NE(errorOf(robot).find("every wheel is a caster"), std::string::npos) << errorOf(robot);
}

TEST(DriveParams, AWheelOutsideTheBodyIsRejectedByTheModelsOwnCheck) {
  const auto robot = cromsci();
  auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  p.wheels[1].x_m = 0.45;
  EXPECT_NE(checkDriveParams(p).find("wheels[1]"), std::string::npos);
  EXPECT_THROW(validateDriveParams(p), ConfigError);
  p = driveParamsFromRobot(robot, computeGeometry(robot));
  p.mass_kg = 0.0;
  EXPECT_NE(checkDriveParams(p).find("mass_kg"), std::string::npos);
  p = driveParamsFromRobot(robot, computeGeometry(robot));
  p.wheels[2].friction_coefficient = -1.0;
  EXPECT_NE(checkDriveParams(p).find("wheels[2].friction_coefficient"), std::string::npos) << checkDriveParams(p);
  p = driveParamsFromRobot(robot, computeGeometry(robot));
  p.wheels[0].trail_m = 0.01;
  EXPECT_NE(checkDriveParams(p).find("wheels[0].trail_m"), std::string::npos) << checkDriveParams(p);
}

TEST(DriveParams, WallOrientationsParse) {
  EXPECT_EQ(WallOrientation::parse("--wall", "floor").gravity_z, -1.0);
  EXPECT_NEAR(WallOrientation::parse("--wall", "overhang:30").gravity_z, 0.5, 1e-12);
  EXPECT_THROW(WallOrientation::parse("--wall", "overhang:abc"), ConfigError);
  EXPECT_THROW(WallOrientation::parse("--wall", "sideways"), ConfigError);
}

}  // namespace
}  // namespace climbsim::drive
