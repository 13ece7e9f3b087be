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
  EXPECT_EQ(p.contact.friction_coefficient, robot.wheels[0].friction_coefficient);
  // The wheel torque limit lets each wheel use its share of the desired downforce's friction.
  EXPECT_NEAR(p.wheel_servo.torque_max_nm * 3.0 / p.wheel_radius_m,
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

TEST(DriveParams, WheelsTheDriveModelDoesNotHaveAreRefusedByName) {
  auto robot = cromsci();
  robot.wheels[2].kind = RobotDescription::WheelKind::kCaster;
  EXPECT_NE(errorOf(robot).find("wheels[3].kind = caster"), std::string::npos) << errorOf(robot);
  robot = cromsci();
  robot.wheels[1].radius_m = 0.04;
  EXPECT_NE(errorOf(robot).find("wheels[2]"), std::string::npos) << errorOf(robot);
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
  p.contact.friction_coefficient = -1.0;
  EXPECT_NE(checkDriveParams(p).find("contact.friction_coefficient"), std::string::npos);
}

TEST(DriveParams, WallOrientationsParse) {
  EXPECT_EQ(WallOrientation::parse("--wall", "floor").gravity_z, -1.0);
  EXPECT_NEAR(WallOrientation::parse("--wall", "overhang:30").gravity_z, 0.5, 1e-12);
  EXPECT_THROW(WallOrientation::parse("--wall", "overhang:abc"), ConfigError);
  EXPECT_THROW(WallOrientation::parse("--wall", "sideways"), ConfigError);
}

}  // namespace
}  // namespace climbsim::drive
