// Every shipped robot in the drive model: steerable, fixed (differential and skid steering)
// and caster wheels, the body kinematics that drives them, the hold and the fall, and the
// chassis inertia of a rectangular body. Expected values are computed here from the robot
// file and the kinematics (v = r omega, rigid body in the wall plane), not by the model.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "drive_command.hpp"
#include "drive_model.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;
constexpr double kPi = 3.14159265358979323846;

RobotDescription robotFile(const std::string& name) {
  return loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml");
}

DriveParams paramsOf(const std::string& name) {
  const auto robot = robotFile(name);
  return driveParamsFromRobot(robot, computeGeometry(robot));
}

std::vector<std::string> shippedRobots() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(CLIMBSIM_ROBOTS_DIR)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  return names;
}

/// Outputs after every step of `seconds` from rest at the origin, yaw 0.
std::vector<DriveOutputs> simulate(const DriveParams& params, const WallOrientation& wall, double seconds,
                                   const std::function<DriveInputs(double)>& schedule) {
  const DriveModel model(params, wall);
  DriveModelState state = model.initialState(StartPose{});
  std::vector<DriveOutputs> out;
  const auto n = static_cast<std::int64_t>(std::llround(seconds * 1e9 / kStepNs));
  for (std::int64_t k = 0; k < n; ++k) {
    out.push_back(model.step(state, schedule(static_cast<double>(k * kStepNs) * 1e-9), k * kStepNs, kStepNs));
  }
  return out;
}

DriveInputs bodyMotion(double downforce_n, double vx, double vy, double wz) {
  DriveInputs in;
  in.downforce_n = downforce_n;
  in.command.vx_mps = vx;
  in.command.vy_mps = vy;
  in.command.wz_radps = wz;
  return in;
}

/// Yaw of R about W's z from the output quaternion (R's z stays along W's z here).
double yawOf(const DriveOutputs& o) {
  const auto& q = o.orientation_wxyz;
  return std::atan2(2.0 * (q[0] * q[3] + q[1] * q[2]), 1.0 - 2.0 * (q[2] * q[2] + q[3] * q[3]));
}

/// A point of R (x, y in the sealing plane) in W's x, y.
std::array<double, 2> inWall(const DriveOutputs& o, double x, double y) {
  const double yaw = yawOf(o);
  return {o.position_m[0] + std::cos(yaw) * x - std::sin(yaw) * y,
          o.position_m[1] + std::sin(yaw) * x + std::cos(yaw) * y};
}

/// Rolling radius of wheel i [m]: the wheel radius less its Hertz penetration under its
/// normal force N, x = (N / ((4/3) E sqrt(r)))^(2/3): the contact point is the centre
/// projected on the wall, r - x below it.
double rollingRadius(const DriveParams& p, const DriveOutputs& o, std::size_t i) {
  const double r = p.wheels[i].radius_m;
  const double x = std::pow(o.wheels[i].normal_force_n / ((4.0 / 3.0) * p.contact.hertz_modulus_pa * std::sqrt(r)),
                            2.0 / 3.0);
  return r - x;
}

const DriveOutputs& at(const std::vector<DriveOutputs>& run, double t_s) {
  return run.at(static_cast<std::size_t>(std::llround(t_s * 1e9 / kStepNs)) - 1);
}

TEST(DriveKinds, EveryShippedRobotGivesValidDriveParamsWithItsWheels) {
  const auto names = shippedRobots();
  ASSERT_GE(names.size(), 4u);
  for (const auto& name : names) {
    const auto robot = robotFile(name);
    const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
    EXPECT_EQ(checkDriveParams(p), "") << name;
    ASSERT_EQ(p.wheels.size(), robot.wheels.size()) << name;
    for (std::size_t i = 0; i < p.wheels.size(); ++i) {
      EXPECT_STREQ(toString(p.wheels[i].kind), toString(robot.wheels[i].kind)) << name << " wheel " << i + 1;
      EXPECT_EQ(p.wheels[i].radius_m, robot.wheels[i].radius_m) << name << " wheel " << i + 1;
      EXPECT_EQ(p.wheels[i].friction_coefficient, robot.wheels[i].friction_coefficient) << name;
      EXPECT_EQ(p.wheels[i].trail_m, p.wheels[i].kind == WheelKind::kCaster ? p.wheels[i].radius_m : 0.0) << name;
    }
    // Every model builds and its robot starts at rest with all wheels on the wall.
    const DriveModel model(p, WallOrientation::vertical());
    EXPECT_EQ(model.initialState(StartPose{}).outputs().wheels.size(), p.wheels.size()) << name;
  }
}

TEST(DriveKinds, ARectangularBodyHasTheInertiaOfAUniformBox) {
  const auto robot = robotFile("grid-2x2");
  ASSERT_EQ(robot.body.shape, RobotDescription::Shape::kRectangle);
  const auto p = paramsOf("grid-2x2");
  // Box of L x B x t, t = 2 h, mass m_c (the drive units' mass taken out).
  const double m = robot.body.mass_kg * (1.0 - 4.0 * p.unit_mass_fraction);
  const double l = robot.body.length_m, b = robot.body.width_m, t = 2.0 * robot.body.com_height_m;
  EXPECT_NEAR(p.inertia_xx_kgm2, m * (b * b + t * t) / 12.0, 1e-12);
  EXPECT_NEAR(p.inertia_yy_kgm2, m * (l * l + t * t) / 12.0, 1e-12);
  EXPECT_NEAR(p.inertia_zz_kgm2, m * (l * l + b * b) / 12.0, 1e-12);
  // Body radius: the outline's farthest point, the rectangle's corner.
  EXPECT_NEAR(p.body_radius_m, 0.5 * std::hypot(l, b), 1e-12);
}

TEST(DriveKinds, FixedWheelsRollAtTheirContactSpeedAlongXAndCastersGetNothing) {
  const auto p = paramsOf("single-chamber");
  DriveCommand c;
  c.vx_mps = 0.03;
  c.vy_mps = 0.02;
  c.wz_radps = 0.2;
  const auto t = wheelTargets(p, c, {});
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(t[i].steering_rad, 0.0);
    EXPECT_NEAR(t[i].wheel_speed_radps * p.wheels[i].radius_m, c.vx_mps - c.wz_radps * p.wheels[i].y_m, 1e-15);
  }
  EXPECT_EQ(t[2].steering_rad, 0.0);
  EXPECT_EQ(t[2].wheel_speed_radps, 0.0);
  // The sideways speed the fixed wheels cannot give is named once, not refused.
  EXPECT_EQ(checkCommand(p, c), "");
  EXPECT_NE(sidewaysNote(p, c).find("fixed wheels (1, 2)"), std::string::npos) << sidewaysNote(p, c);
  c.vy_mps = 0.0;
  EXPECT_EQ(sidewaysNote(p, c), "");
  EXPECT_EQ(sidewaysNote(paramsOf("cromsci"), bodyMotion(0, 0, 0.05, 0).command), "");
  // Per-wheel set-points: a fixed wheel is not steered, a caster not driven.
  DriveCommand w;
  w.steering_rad = {0.0, 0.0, 0.0};
  w.wheel_speed_radps = {1.0, -1.0, 0.0};
  EXPECT_EQ(checkCommand(p, w), "");
  w.steering_rad[0] = 0.1;
  EXPECT_NE(checkCommand(p, w).find("wheel 1 is fixed"), std::string::npos) << checkCommand(p, w);
  w.steering_rad[0] = 0.0;
  w.wheel_speed_radps[2] = 1.0;
  EXPECT_NE(checkCommand(p, w).find("wheel 3 is a caster"), std::string::npos) << checkCommand(p, w);
}

/// The differential-drive robot on a floor (no gravity along the wall) at its set-point.
std::vector<DriveOutputs> differential(double vx, double wz, double seconds) {
  const auto robot = robotFile("single-chamber");
  const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  const double f = robot.adhesion.desired_downforce_n;
  return simulate(p, WallOrientation::floor(), seconds, [&](double) { return bodyMotion(f, vx, 0.0, wz); });
}

TEST(DriveKinds, ADifferentialDriveWithVxMovesStraightAlongX) {
  const auto p = paramsOf("single-chamber");
  const double vx = 0.05;
  const auto run = differential(vx, 0.0, 4.0);
  const auto &a = at(run, 2.0), &b = at(run, 4.0);
  const double speed = (b.position_m[0] - a.position_m[0]) / 2.0;
  std::printf("  differential vx %.3f m/s: body %.5f m/s, sideways %.2e m, yaw %.2e rad\n", vx, speed, b.position_m[1],
              yawOf(b));
  EXPECT_NEAR(speed, vx, 0.03 * vx);  // the wheels roll at the command on their loaded radius
  EXPECT_LT(std::fabs(b.position_m[1]), 1e-3) << "drifts sideways";
  EXPECT_LT(std::fabs(yawOf(b)), 1e-3) << "turns";
  // v = r omega of each driven wheel, and the caster follows: it rolls at the body speed too.
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(b.wheels[i].wheel_speed_radps * rollingRadius(p, b, i), speed, 0.002 * vx) << "wheel " << i + 1;
  }
  EXPECT_LT(std::fabs(b.wheels[2].steering_rad), 0.01) << "the caster trails straight behind";
  EXPECT_FALSE(b.fell);
}

TEST(DriveKinds, ADifferentialDriveWithWzTurnsOnTheSpotAboutItsAxleMidpoint) {
  const auto p = paramsOf("single-chamber");
  const double wz = 0.3;
  const auto run = differential(0.0, wz, 4.0);
  const auto &a = at(run, 2.0), &b = at(run, 3.0);
  const double rate = std::remainder(yawOf(b) - yawOf(a), 2.0 * kPi) / 1.0;
  // The kinematics: wheel i's contact rolls at v_i = omega_i r_i = -wz y_i, so
  // wz = (v_2 - v_1) / (y_1 - y_2) from the measured wheel speeds on their loaded radius.
  const double v1 = b.wheels[0].wheel_speed_radps * rollingRadius(p, b, 0);
  const double v2 = b.wheels[1].wheel_speed_radps * rollingRadius(p, b, 1);
  EXPECT_NEAR(rate, (v2 - v1) / (p.wheels[0].y_m - p.wheels[1].y_m), 0.005 * wz);
  EXPECT_NEAR(rate, wz, 0.05 * wz);  // the command, less the loaded radius (2.5 %) and the caster's drag
  // The axle's midpoint (between the fixed wheels) stays where it started.
  const double mx = 0.5 * (p.wheels[0].x_m + p.wheels[1].x_m), my = 0.5 * (p.wheels[0].y_m + p.wheels[1].y_m);
  const auto end = at(run, 4.0);
  const auto mid = inWall(end, mx, my);
  std::printf("  differential wz %.2f rad/s: yaw rate %.4f rad/s, axle midpoint moved %.2e m, caster %.4f rad\n", wz,
              rate, std::hypot(mid[0] - mx, mid[1] - my), b.wheels[2].steering_rad);
  EXPECT_LT(std::hypot(mid[0] - mx, mid[1] - my), 5e-3) << "midpoint at (" << mid[0] << ", " << mid[1] << ")";
  // Each fixed wheel rolls at v = -wz y_i = r omega_i; the caster swivels across (its contact
  // moves along R's y about the midpoint).
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(b.wheels[i].wheel_speed_radps * rollingRadius(p, b, i), -rate * p.wheels[i].y_m, 0.01 * wz * 0.17)
        << "wheel " << i + 1;
  }
  // The caster's contact, trail d behind its swivel axis at distance R from the midpoint,
  // rolls on a circle about the midpoint: its heading is 90° less asin(d / R) across R's x.
  const double swivel_r = std::hypot(p.wheels[2].x_m - mx, p.wheels[2].y_m - my);
  const double heading = kPi / 2.0 - std::asin(p.wheels[2].trail_m / swivel_r);
  EXPECT_NEAR(std::fabs(std::remainder(b.wheels[2].steering_rad, kPi)), heading, 0.01) << "caster heading";
  EXPECT_FALSE(end.fell);
}

TEST(DriveKinds, ASkidSteeredGridRobotMovesAlongXWithVx) {
  const auto robot = robotFile("grid-2x2");
  const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  const double vx = 0.05, f = robot.adhesion.desired_downforce_n;
  const auto run = simulate(p, WallOrientation::floor(), 4.0, [&](double) { return bodyMotion(f, vx, 0.0, 0.0); });
  const auto &a = at(run, 2.0), &b = at(run, 4.0);
  const double speed = (b.position_m[0] - a.position_m[0]) / 2.0;
  std::printf("  skid-steered vx %.3f m/s: body %.5f m/s, sideways %.2e m, yaw %.2e rad\n", vx, speed, b.position_m[1],
              yawOf(b));
  EXPECT_NEAR(speed, vx, 0.03 * vx);
  EXPECT_LT(std::fabs(b.position_m[1]), 1e-3);
  EXPECT_LT(std::fabs(yawOf(b)), 1e-3);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(b.wheels[i].wheel_speed_radps * rollingRadius(p, b, i), speed, 0.002 * vx) << "wheel " << i + 1;
  }
}

/// Yaw rate of a skid-steered robot turning on the spot, from the moment balance of Coulomb
/// friction (every wheel slides: the bristles saturate above a few mm/s of slip): wheel i at
/// (x_i, y_i) with its tread moving at u_i along R's x, the body turning at W about its centre,
/// slips at s_i = (-W y_i - u_i, W x_i) and feels f_i = -mu N_i s_i / |s_i|; the friction's yaw
/// moment sum (x_i f_iy - y_i f_ix) balances the sealing drag's -D R (W R) / sqrt((W R)² + eps²).
/// Bisection on W in (0, w_max): the moment falls as W grows.
double skidSteerYawRate(const DriveParams& p, const std::vector<double>& tread_mps, const std::vector<double>& normal_n,
                        double downforce_n, double w_max) {
  const auto excess = [&](double w) {
    double moment = 0.0;
    for (std::size_t i = 0; i < p.wheels.size(); ++i) {
      const double x = p.wheels[i].x_m, y = p.wheels[i].y_m;
      const double sx = -w * y - tread_mps[i], sy = w * x;
      moment -= p.wheels[i].friction_coefficient * normal_n[i] * (x * sy - y * sx) / std::hypot(sx, sy);
    }
    const double drag = p.sealing_drag_coefficient * downforce_n, rim = w * p.body_radius_m;
    return moment - drag * p.body_radius_m * rim / std::sqrt(rim * rim + p.drag_regularisation_mps * p.drag_regularisation_mps);
  };
  double lo = 1e-9, hi = w_max;
  for (int k = 0; k < 60; ++k) (excess(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

TEST(DriveKinds, ASkidSteeredGridRobotTurnsOnTheSpotAsItsSlidingWheelsAllow) {
  const auto robot = robotFile("grid-2x2");
  const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
  const double wz = 0.3, f = robot.adhesion.desired_downforce_n;
  const auto run = simulate(p, WallOrientation::floor(), 4.0, [&](double) { return bodyMotion(f, 0.0, 0.0, wz); });
  const auto &a = at(run, 2.0), &b = at(run, 3.0), &end = at(run, 4.0);
  const double rate = std::remainder(yawOf(b) - yawOf(a), 2.0 * kPi) / 1.0;
  // The treads roll as the kinematics asks (v = -wz y_i on the loaded radius); the wheels
  // share the downforce and the weight equally (floor, symmetric robot).
  std::vector<double> tread, normal;
  const double load = (f + p.mass_kg * p.gravity_mps2) / 4.0;
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(b.wheels[i].wheel_speed_radps * p.wheels[i].radius_m, -wz * p.wheels[i].y_m, 1e-3 * wz) << i + 1;
    tread.push_back(b.wheels[i].wheel_speed_radps * rollingRadius(p, b, i));
    normal.push_back(load);
  }
  const double expected = skidSteerYawRate(p, tread, normal, f, wz);
  std::printf("  skid-steered wz %.2f rad/s: yaw rate %.4f rad/s (Coulomb moment balance %.4f), centre moved %.2e m\n",
              wz, rate, expected, std::hypot(end.position_m[0], end.position_m[1]));
  EXPECT_NEAR(rate, expected, 0.03 * expected);
  EXPECT_LT(std::hypot(end.position_m[0], end.position_m[1]), 1e-3) << "turns about its centre";
}

TEST(DriveKinds, EveryShippedRobotHoldsOnAVerticalWallAtItsSetPointAndFallsWithoutDownforce) {
  for (const auto& name : shippedRobots()) {
    const auto robot = robotFile(name);
    const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
    const double f = robot.adhesion.desired_downforce_n;
    const auto held = simulate(p, WallOrientation::vertical(), 2.0, [&](double) { return bodyMotion(f, 0, 0, 0); });
    const auto& end = held.back();
    EXPECT_FALSE(end.fell) << name;
    EXPECT_LT(std::hypot(end.position_m[0], end.position_m[1]), 2e-3) << name << " slides";
    EXPECT_LT(std::hypot(end.linear_velocity_mps[0], end.linear_velocity_mps[1]), 1e-3) << name;

    const auto dropped = simulate(p, WallOrientation::vertical(), 2.0, [&](double) { return bodyMotion(0, 0, 0, 0); });
    const auto fell = std::find_if(dropped.begin(), dropped.end(), [](const DriveOutputs& o) { return o.fell; });
    std::printf("  %-15s at %6.0f N: moved %.2e m in 2 s; without downforce fell at %.3f s\n", name.c_str(), f,
                std::hypot(end.position_m[0], end.position_m[1]),
                fell == dropped.end() ? -1.0 : static_cast<double>(fell->t_ns) * 1e-9);
    EXPECT_TRUE(dropped.back().fell) << name;
    EXPECT_LT(dropped.back().position_m[1], -0.01) << name << " did not slide down";
  }
}

TEST(DriveKinds, EveryShippedRobotSlidesBelowItsFrictionLimitAndHoldsAboveIt) {
  // On a vertical wall friction must carry the weight: mu F >= m g at the least (more where a
  // caster takes part of F and no tangential load). Half that slides; twice that holds.
  for (const auto& name : shippedRobots()) {
    const auto p = paramsOf(name);
    const double limit_n = p.mass_kg * p.gravity_mps2 / p.wheels.front().friction_coefficient;
    const auto slides = simulate(p, WallOrientation::vertical(), 2.0, [&](double) {
      return bodyMotion(0.5 * limit_n, 0, 0, 0);
    });
    const auto holds = simulate(p, WallOrientation::vertical(), 2.0, [&](double) {
      return bodyMotion(2.0 * limit_n, 0, 0, 0);
    });
    std::printf("  %-15s at %4.0f N slid %.3f m (fell %d), at %4.0f N %.2e m\n", name.c_str(), 0.5 * limit_n,
                -slides.back().position_m[1], slides.back().fell ? 1 : 0, 2.0 * limit_n, -holds.back().position_m[1]);
    EXPECT_LT(slides.back().position_m[1], -0.05) << name << " does not slide";
    EXPECT_GT(holds.back().position_m[1], -5e-3) << name << " slides";
    EXPECT_FALSE(holds.back().fell) << name;
  }
}

TEST(DriveKinds, EveryShippedRobotHeldWhileTheVacuumBuildsStaysPutWhenReleased) {
  // The hold's friction solution (driven wheels only: a caster carries no tangential load)
  // must carry the weight, so that the release moves the robot by less than a millimetre.
  for (const auto& name : shippedRobots()) {
    const auto robot = robotFile(name);
    const auto p = driveParamsFromRobot(robot, computeGeometry(robot));
    const double f = robot.adhesion.desired_downforce_n;
    const auto run = simulate(p, WallOrientation::vertical(), 1.5, [&](double t) {
      DriveInputs in = bodyMotion(f * (1.0 - std::exp(-t / 0.3)), 0, 0, 0);
      in.held = t < 1.0;
      return in;
    });
    const auto& released = at(run, 1.0);
    double moved = 0.0;
    for (const auto& o : run) {
      if (o.t_ns <= released.t_ns) continue;
      moved = std::max(moved, std::hypot(o.position_m[0] - released.position_m[0],
                                         o.position_m[1] - released.position_m[1]));
    }
    std::printf("  %-15s released: moved %.2e m in 0.5 s\n", name.c_str(), moved);
    EXPECT_LT(moved, 1e-3) << name;
    EXPECT_FALSE(run.back().fell) << name;
  }
}

}  // namespace
}  // namespace climbsim::drive
