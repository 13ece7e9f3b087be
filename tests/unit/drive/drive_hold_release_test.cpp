// The hold at the start of a scenario and its release: while held the wheels
// take the downforce and their friction carries the weight in static equilibrium, so releasing
// the robot moves it by less than a millimetre, without a wheel bouncing.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "drive_model.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;
constexpr double kPi = 3.14159265358979323846;

const DriveParams& cromsci() {
  static const DriveParams params = [] {
    const auto robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
    return driveParamsFromRobot(robot, computeGeometry(robot));
  }();
  return params;
}

/// The vacuum building up while the robot is held: F rises to 2200 N with a time constant
/// of 0.3 s (the engines' lag and the valves' stroke), P_F a few mm off the centre.
DriveInputs vacuum(double t_s) {
  DriveInputs in;
  in.downforce_n = 2200.0 * (1.0 - std::exp(-t_s / 0.3));
  in.pf_x_m = 0.004;
  in.pf_y_m = -0.003;
  return in;
}

/// Normal forces of the three wheels in static equilibrium on a vertical wall (W's y up) at yaw
/// psi: sum N_i = F and the moments about R's x and y of the normal forces, the adhesion at P_F
/// and the weight m g at the centre of mass (height h), with g_R = g (-sin psi, -cos psi):
///   sum y_i N_i = F pf_y + m h g_Ry,   sum x_i N_i = F pf_x + m h g_Rx.
std::array<double, 3> staticNormalForces(const DriveParams& p, const DriveInputs& in, double yaw) {
  const double gx = -p.gravity_mps2 * std::sin(yaw), gy = -p.gravity_mps2 * std::cos(yaw);
  const double f = in.downforce_n;
  const double b[3] = {f, f * in.pf_y_m + p.mass_kg * p.com_height_m * gy, f * in.pf_x_m + p.mass_kg * p.com_height_m * gx};
  double a[3][3];
  for (int i = 0; i < 3; ++i) {
    a[0][i] = 1.0;
    a[1][i] = p.wheels[static_cast<std::size_t>(i)].y_m;
    a[2][i] = p.wheels[static_cast<std::size_t>(i)].x_m;
  }
  const auto det = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det(a);
  std::array<double, 3> n{};
  for (int c = 0; c < 3; ++c) {
    double m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) m[r][k] = k == c ? b[r] : a[r][k];
    n[static_cast<std::size_t>(c)] = det(m) / d;
  }
  return n;
}

struct Release {
  DriveOutputs held;             ///< at the end of the hold
  double max_in_plane_m = 0.0;   ///< largest move along the wall in the 100 ms after release
  double max_normal_m = 0.0;     ///< largest move along the wall normal in those 100 ms
  double min_load_ratio = 1e9;   ///< smallest wheel load / its held load in those 100 ms
  double max_load_ratio = 0.0;
  DriveOutputs after_100ms;
  DriveOutputs later;            ///< 1 s after release
};

Release holdAndRelease(const WallOrientation& wall, double yaw_rad) {
  const DriveModel model(cromsci(), wall);
  DriveModelState state = model.initialState(StartPose{1.0, 1.2, yaw_rad});
  const auto input = [](std::int64_t t, bool held) {
    DriveInputs in = vacuum(static_cast<double>(t) * 1e-9);
    in.held = held;
    return in;
  };
  std::int64_t t = 0;
  for (; t < 2'000'000'000; t += kStepNs) model.step(state, input(t, true), t, kStepNs);
  Release r;
  r.held = state.outputs();
  for (; t < 2'100'000'000; t += kStepNs) {
    const DriveOutputs o = model.step(state, input(t, false), t, kStepNs);
    r.max_in_plane_m = std::max(r.max_in_plane_m, std::hypot(o.position_m[0] - r.held.position_m[0],
                                                             o.position_m[1] - r.held.position_m[1]));
    r.max_normal_m = std::max(r.max_normal_m, std::abs(o.position_m[2] - r.held.position_m[2]));
    for (std::size_t i = 0; i < o.wheels.size(); ++i) {
      const double ratio = o.wheels[i].normal_force_n / r.held.wheels[i].normal_force_n;
      r.min_load_ratio = std::min(r.min_load_ratio, ratio);
      r.max_load_ratio = std::max(r.max_load_ratio, ratio);
    }
  }
  r.after_100ms = state.outputs();
  for (; t < 3'000'000'000; t += kStepNs) model.step(state, input(t, false), t, kStepNs);
  r.later = state.outputs();
  return r;
}

TEST(DriveHoldRelease, HeldWheelsCarryTheDownforce) {
  const Release r = holdAndRelease(WallOrientation::vertical(), -kPi / 2);
  double sum = 0.0;
  for (const auto& w : r.held.wheels) {
    EXPECT_GT(w.normal_force_n, 0.0);
    sum += w.normal_force_n;
  }
  // Static balance along the wall normal: the wheels push back what the vacuum pulls.
  EXPECT_NEAR(sum, vacuum(2.0).downforce_n, 0.01 * vacuum(2.0).downforce_n);
  EXPECT_LT(r.held.position_m[2], 0.0);  // pressed in, by the tyres' compliance
  EXPECT_FALSE(r.held.fell);
}

TEST(DriveHoldRelease, ReleaseMovesTheRobotLessThanAMillimetreWithoutBounce) {
  for (const double yaw : {-kPi / 2, 0.0, 0.7}) {
    const Release r = holdAndRelease(WallOrientation::vertical(), yaw);
    RecordProperty("max_in_plane_m_yaw_" + std::to_string(yaw), std::to_string(r.max_in_plane_m));
    RecordProperty("max_normal_m_yaw_" + std::to_string(yaw), std::to_string(r.max_normal_m));
    EXPECT_LT(r.max_in_plane_m, 1e-3) << "yaw " << yaw;
    EXPECT_LT(r.max_normal_m, 1e-3) << "yaw " << yaw;
    // Released, the weight's tipping moment shifts load between the wheels (the hand held the
    // attitude); they go to the loads of static equilibrium without losing contact or bouncing.
    EXPECT_GT(r.min_load_ratio, 0.5) << "yaw " << yaw;
    const auto statics = staticNormalForces(cromsci(), vacuum(2.1), yaw);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(r.after_100ms.wheels[i].normal_force_n, statics[i], 0.05 * 2200.0 / 3.0) << "yaw " << yaw << " wheel " << i;
    }
    // And it stays: 1 s later it has not crept away either.
    EXPECT_LT(std::hypot(r.later.position_m[0] - r.held.position_m[0], r.later.position_m[1] - r.held.position_m[1]),
              1e-3)
        << "yaw " << yaw;
    EXPECT_FALSE(r.later.fell);
  }
}

TEST(DriveHoldRelease, OnAnOverhangTheHoldKeepsTheRobotFromLiftingOff) {
  // Gravity pulls the robot off a 60° overhang until the vacuum holds it; the hand keeps it on.
  const Release r = holdAndRelease(WallOrientation::overhang(60.0), 0.0);
  EXPECT_LE(r.held.position_m[2], 0.0);
  EXPECT_LT(r.max_in_plane_m, 1e-3);
  EXPECT_FALSE(r.later.fell);
}

}  // namespace
}  // namespace climbsim::drive
