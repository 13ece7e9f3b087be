// Physics of the drive model (Simbody): holding, the friction limit, load distribution,
// slip, paths, the floor, falling, determinism. The long runs are made once and checked for
// several facts each.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>

#include "drive_model.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;  // the exchange period of the default scenario

const DriveParams& cromsci() {
  static const DriveParams params = [] {
    const auto robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml");
    return driveParamsFromRobot(robot, computeGeometry(robot));
  }();
  return params;
}

/// A run: the outputs after every step of `seconds`, inputs from `schedule(t_s)`.
struct Run {
  std::vector<DriveOutputs> steps;
  const DriveOutputs& at(double t_s) const {
    return steps.at(static_cast<std::size_t>(std::llround(t_s * 1e9 / kStepNs)) - 1);
  }
};

Run simulate(double seconds, const std::function<DriveInputs(double)>& schedule,
             const WallOrientation& wall = WallOrientation::vertical(), const DriveParams& params = cromsci()) {
  const DriveModel model(params, wall);
  DriveModelState state = model.initialState(StartPose{});
  Run run;
  const auto n = static_cast<std::int64_t>(std::llround(seconds * 1e9 / kStepNs));
  for (std::int64_t k = 0; k < n; ++k) {
    run.steps.push_back(model.step(state, schedule(static_cast<double>(k * kStepNs) * 1e-9), k * kStepNs, kStepNs));
  }
  return run;
}

DriveInputs adhesion(double downforce_n, double pf_x_m = 0.0, double pf_y_m = 0.0) {
  DriveInputs in;
  in.downforce_n = downforce_n;
  in.pf_x_m = pf_x_m;
  in.pf_y_m = pf_y_m;
  return in;
}

double distance(const DriveOutputs& a, const DriveOutputs& b) {
  return std::hypot(a.position_m[0] - b.position_m[0], a.position_m[1] - b.position_m[1]);
}

double yaw(const DriveOutputs& o) {
  const auto& q = o.orientation_wxyz;
  return std::atan2(2.0 * (q[0] * q[3] + q[1] * q[2]), 1.0 - 2.0 * (q[2] * q[2] + q[3] * q[3]));
}

/// Normal forces of three wheels from the three equilibrium equations of the robot at rest
/// on a vertical wall (W's y up): sum N = F; moments about R's x and y of the normal forces,
/// the adhesion at P_F and the weight at the centre of mass (height h):
///   sum y_i N_i = F pf_y - m g h,   sum x_i N_i = F pf_x.
std::array<double, 3> staticNormalForces(const DriveParams& p, double f, double pf_x, double pf_y) {
  const double b[3] = {f, f * pf_y - p.mass_kg * p.gravity_mps2 * p.com_height_m, f * pf_x};
  double a[3][3];
  for (int i = 0; i < 3; ++i) {
    a[0][i] = 1.0;
    a[1][i] = p.wheels[static_cast<std::size_t>(i)].y_m;
    a[2][i] = p.wheels[static_cast<std::size_t>(i)].x_m;
  }
  // Cramer's rule.
  const auto det = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det(a);
  std::array<double, 3> n{};
  for (int c = 0; c < 3; ++c) {
    double m[3][3];
    std::memcpy(m, a, sizeof(a));
    for (int r = 0; r < 3; ++r) m[r][c] = b[r];
    n[static_cast<std::size_t>(c)] = det(m) / d;
  }
  return n;
}

const Run& restRun() {
  static const Run run = simulate(10.5, [](double) { return adhesion(2200.0); });
  return run;
}

TEST(DriveModel, AtRestOnAVerticalWallTheRobotStays) {
  const auto& run = restRun();
  const auto& settled = run.at(0.5);
  const auto& end = run.at(10.5);
  EXPECT_LT(distance(settled, end), 1e-3) << "drift in 10 s";
  EXPECT_LT(distance(run.at(0.005), end), 5e-3) << "elastic sag";
  EXPECT_FALSE(end.fell);
  EXPECT_NEAR(end.position_m[2], 0.0, 3e-3);  // on the wall, pressed in by about a millimetre
}

TEST(DriveModel, NormalForcesBalanceTheAdhesionAndTheWeightsMoment) {
  const auto& end = restRun().at(10.5);
  const auto expected = staticNormalForces(cromsci(), 2200.0, 0.0, 0.0);
  double sum = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    sum += end.wheels[i].normal_force_n;
    // 3 %: the contact points sit about a millimetre inside the wall plane.
    EXPECT_NEAR(end.wheels[i].normal_force_n, expected[i], 0.03 * 2200.0 / 3.0) << "wheel " << i + 1;
  }
  EXPECT_NEAR(sum, 2200.0, 1e-3 * 2200.0);
  // The weight tips the top away: the upper wheel (chamber 3, y > 0) carries less.
  EXPECT_LT(end.wheels[1].normal_force_n, end.wheels[2].normal_force_n);
}

TEST(DriveModel, NormalForcesShiftTowardsThePointOfAction) {
  const auto shifted = simulate(1.0, [](double) { return adhesion(2200.0, 0.1, 0.0); }).steps.back();
  const auto& centred = restRun().at(1.0);
  const auto expected = staticNormalForces(cromsci(), 2200.0, 0.1, 0.0);
  EXPECT_GT(shifted.wheels[0].normal_force_n, centred.wheels[0].normal_force_n + 200.0);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(shifted.wheels[i].normal_force_n, expected[i], 0.03 * 2200.0 / 3.0) << "wheel " << i + 1;
  }
}

/// The robot holds: after 1.5 s it has moved less than 5 mm and has not fallen.
bool holds(double downforce_n) {
  const auto run = simulate(1.5, [&](double) { return adhesion(downforce_n); });
  return !run.steps.back().fell && distance(run.steps.front(), run.steps.back()) < 5e-3;
}

TEST(DriveModel, TheSmallestHoldingDownforceIsTheWeightOverTheFrictionCoefficient) {
  const auto& p = cromsci();
  const double analytic = p.mass_kg * p.gravity_mps2 / p.wheels[0].friction_coefficient;
  double lo = 0.25 * analytic, hi = 2.0 * analytic;
  ASSERT_FALSE(holds(lo));
  ASSERT_TRUE(holds(hi));
  for (int k = 0; k < 7; ++k) {
    const double mid = 0.5 * (lo + hi);
    (holds(mid) ? hi : lo) = mid;
  }
  EXPECT_NEAR(0.5 * (lo + hi), analytic, 0.10 * analytic) << "bracket [" << lo << ", " << hi << "]";
}

/// Mean slip of all wheels over [from, to] s.
double meanSlip(const Run& run, double from, double to) {
  double sum = 0.0;
  int n = 0;
  for (const auto& o : run.steps) {
    const double t = static_cast<double>(o.t_ns) * 1e-9;
    if (t < from || t > to) continue;
    for (const auto& w : o.wheels) sum += w.slip_mps;
    n += 3;
  }
  return sum / n;
}

TEST(DriveModel, DrivingUpSlipsMoreThanDrivingDown) {
  const auto drive = [](double vy) {
    return simulate(4.0, [vy](double) {
      auto in = adhesion(2200.0);
      in.command.vy_mps = vy;
      return in;
    });
  };
  const auto up = drive(0.05);
  const auto down = drive(-0.05);
  // Both moved about as commanded once steered (the first second turns the wheels).
  EXPECT_NEAR(up.at(4.0).position_m[1] - up.at(2.0).position_m[1], 0.1, 0.01);
  EXPECT_NEAR(down.at(4.0).position_m[1] - down.at(2.0).position_m[1], -0.1, 0.01);
  const double slip_up = meanSlip(up, 2.0, 4.0);
  const double slip_down = meanSlip(down, 2.0, 4.0);
  EXPECT_GT(slip_up, 1.1 * slip_down) << "up " << slip_up << " m/s, down " << slip_down << " m/s";
  EXPECT_GT(slip_down, 0.0);
}

TEST(DriveModel, ASquarePathReturnsNearItsStart) {
  // Four legs of 3 s at 0.05 m/s: up, left, down, right (body frame = W at the start), each
  // beginning with the wheels turning 90 degrees, so that all legs are alike.
  const auto run = simulate(12.0, [](double t) {
    auto in = adhesion(2200.0);
    const int leg = std::min(3, static_cast<int>(t / 3.0));
    const double vx[4] = {0.0, -0.05, 0.0, 0.05};
    const double vy[4] = {0.05, 0.0, -0.05, 0.0};
    in.command.vx_mps = vx[leg];
    in.command.vy_mps = vy[leg];
    return in;
  });
  const double corner = distance(run.steps.front(), run.at(6.0));
  EXPECT_GT(corner, 0.1) << "the path should span a square of about 0.1 m sides";
  EXPECT_LT(distance(run.steps.front(), run.steps.back()), 0.02);
  EXPECT_FALSE(run.steps.back().fell);
}

TEST(DriveModel, APureRotationKeepsTheCentreInPlace) {
  // One second to steer the wheels tangentially, then 3 s of rotation at 0.3 rad/s.
  const auto run = simulate(4.0, [](double) {
    auto in = adhesion(2200.0);
    in.command.wz_radps = 0.3;
    return in;
  });
  EXPECT_GT(yaw(run.steps.back()) - yaw(run.steps.front()), 0.7);
  EXPECT_LT(distance(run.steps.front(), run.steps.back()), 0.01);
}

TEST(DriveModel, OnAFloorTheRobotDrivesWithoutAdhesion) {
  const auto run = simulate(
      3.0,
      [](double) {
        DriveInputs in;
        in.command.vx_mps = 0.1;
        return in;
      },
      WallOrientation::floor());
  const auto& end = run.steps.back();
  EXPECT_FALSE(end.fell);
  EXPECT_NEAR(end.position_m[0], 0.3, 0.03);  // 3 s at 0.1 m/s, no steering needed
  EXPECT_NEAR(end.position_m[1], 0.0, 0.005);
  double sum = 0.0;
  for (const auto& w : end.wheels) sum += w.normal_force_n;
  EXPECT_NEAR(sum, cromsci().mass_kg * cromsci().gravity_mps2, 0.01 * sum);
}

TEST(DriveModel, WithoutAdhesionOnAVerticalWallTheRobotFalls) {
  const auto run = simulate(1.0, [](double) { return adhesion(0.0); });
  EXPECT_TRUE(run.steps.back().fell);
  EXPECT_FALSE(run.steps.front().fell);
}

TEST(DriveModel, AHeldRobotStaysAtItsStartUntilReleasedThenFallsWithoutAdhesion) {
  const DriveModel model(cromsci(), WallOrientation::vertical());
  DriveModelState state = model.initialState(StartPose{0.5, 1.0, 0.3});
  DriveInputs in = adhesion(0.0);
  in.held = true;
  std::int64_t t = 0;
  for (; t < 1'000'000'000; t += kStepNs) model.step(state, in, t, kStepNs);
  const auto held = state.outputs();
  EXPECT_FALSE(held.fell);
  EXPECT_EQ(held.position_m[0], 0.5);
  EXPECT_EQ(held.position_m[1], 1.0);
  EXPECT_EQ(held.linear_velocity_mps[1], 0.0);
  in.held = false;
  for (; t < 2'000'000'000; t += kStepNs) model.step(state, in, t, kStepNs);
  // Released without adhesion: it slides down the wall under gravity and leaves it.
  EXPECT_LT(state.outputs().position_m[1], 1.0 - 0.5);
  EXPECT_TRUE(state.outputs().fell);
}

TEST(DriveModel, EqualInputsGiveBitIdenticalOutputs) {
  const auto schedule = [](double t) {
    auto in = adhesion(1500.0 + 500.0 * std::sin(t), 0.02, -0.01);
    in.command.vx_mps = t < 1.0 ? 0.05 : -0.02;
    in.command.wz_radps = 0.1;
    return in;
  };
  const auto a = simulate(2.0, schedule);
  const auto b = simulate(2.0, schedule);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    const auto& x = a.steps[k];
    const auto& y = b.steps[k];
    ASSERT_EQ(std::memcmp(x.position_m.data(), y.position_m.data(), sizeof(x.position_m)), 0) << k;
    ASSERT_EQ(std::memcmp(x.orientation_wxyz.data(), y.orientation_wxyz.data(), sizeof(x.orientation_wxyz)), 0);
    ASSERT_EQ(std::memcmp(x.linear_velocity_mps.data(), y.linear_velocity_mps.data(), sizeof(x.linear_velocity_mps)),
              0);
    for (std::size_t i = 0; i < x.wheels.size(); ++i) {
      ASSERT_EQ(std::memcmp(&x.wheels[i], &y.wheels[i], sizeof(WheelOutputs)), 0) << k << " wheel " << i;
    }
  }
}

TEST(DriveModel, UnusableInputsAndGapsInTimeAreRefused) {
  const DriveModel model(cromsci(), WallOrientation::vertical());
  DriveModelState state = model.initialState(StartPose{});
  auto in = adhesion(2200.0);
  model.step(state, in, 0, kStepNs);
  const DriveOutputs before = state.outputs();
  in.command.vx_mps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(model.step(state, in, kStepNs, kStepNs), std::invalid_argument);
  in = adhesion(std::numeric_limits<double>::infinity());
  EXPECT_THROW(model.step(state, in, kStepNs, kStepNs), std::invalid_argument);
  EXPECT_THROW(model.step(state, adhesion(2200.0), 3 * kStepNs, kStepNs), std::invalid_argument);
  EXPECT_THROW(model.step(state, adhesion(2200.0), kStepNs, 0), std::invalid_argument);
  // A refused step leaves the state as it was.
  EXPECT_EQ(state.t_ns(), kStepNs);
  EXPECT_EQ(state.outputs().position_m, before.position_m);
  EXPECT_NO_THROW(model.step(state, adhesion(2200.0), kStepNs, kStepNs));
}

}  // namespace
}  // namespace climbsim::drive
