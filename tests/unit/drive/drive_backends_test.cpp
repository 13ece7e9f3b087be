// The two force backends of the drive model (ContactBackend) give the same physics: the
// direct one (the model's own forces from Simbody's kinematics, the default) against the
// reference through Simbody's CompliantContactSubsystem and force elements, on the physics
// scenarios of drive_model_test.cpp, compared at every step.
//
// Tolerance: every output agrees to kRelativeTolerance = 1e-12 of its scale (the largest
// magnitude it reaches in the reference run, at least 1 in SI units: m, m/s, rad/s, N). The
// backends evaluate the same equations at the same points, but in a different order of
// floating-point operations (Simbody's contact geometry, force accumulation and forward
// dynamics against the model's own), so they agree to round-off, not bit for bit: at most
// 7e-14 of the scale over these runs (up to 1.2e4 substeps of a stiff, dissipative system). A modelling difference (the contact point off by the penetration, a
// force term missing or at another point, friction in another direction) shows at 1e-3..1e-7.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "climbsim/errors.hpp"
#include "drive_model.hpp"
#include "params_from_robot.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;  // the exchange period of the default scenario
constexpr double kRelativeTolerance = 1e-12;

/// The drive parameters of a shipped robot with `backend`.
DriveParams shipped(ContactBackend backend, const std::string& name = "cromsci") {
  const auto robot = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml");
  DriveParams p = driveParamsFromRobot(robot, computeGeometry(robot));
  p.contact_backend = backend;
  return p;
}

DriveInputs adhesion(double downforce_n) {
  DriveInputs in;
  in.downforce_n = downforce_n;
  return in;
}

/// One kind of output over a run: the largest difference between the backends and the
/// largest magnitude in the reference.
struct Compared {
  const char* name;
  double difference = 0.0;
  double scale = 1.0;  ///< at least 1 (SI unit)

  void add(double direct, double reference) {
    difference = std::max(difference, std::fabs(direct - reference));
    scale = std::max(scale, std::fabs(reference));
  }
  double relative() const { return difference / scale; }
};

struct Comparison {
  Compared position_m{"position [m]"};
  Compared orientation{"orientation (quaternion)"};
  Compared linear_velocity_mps{"linear velocity [m/s]"};
  Compared angular_velocity_radps{"angular velocity [rad/s]"};
  Compared normal_force_n{"wheel normal force [N]"};
  Compared slip_mps{"wheel slip [m/s]"};
  Compared steering_rad{"steering angle [rad]"};
  Compared wheel_speed_radps{"wheel speed [rad/s]"};
  int fell_differs = 0;  ///< steps where one backend had fallen and the other not
  bool fell = false;     ///< the reference fell
  double largest_normal_force_n = 0.0;

  std::vector<const Compared*> all() const {
    return {&position_m, &orientation,      &linear_velocity_mps, &angular_velocity_radps,
            &normal_force_n, &slip_mps, &steering_rad, &wheel_speed_radps};
  }
};

Comparison compare(double seconds, const std::function<DriveInputs(double)>& schedule,
                   const WallOrientation& wall = WallOrientation::vertical(), const std::string& robot = "cromsci") {
  const DriveModel direct(shipped(ContactBackend::kDirect, robot), wall);
  const DriveModel reference(shipped(ContactBackend::kSimbody, robot), wall);
  DriveModelState direct_state = direct.initialState(StartPose{});
  DriveModelState reference_state = reference.initialState(StartPose{});
  Comparison c;
  const auto n = static_cast<std::int64_t>(std::llround(seconds * 1e9 / kStepNs));
  for (std::int64_t k = 0; k < n; ++k) {
    const DriveInputs in = schedule(static_cast<double>(k * kStepNs) * 1e-9);
    const DriveOutputs a = direct.step(direct_state, in, k * kStepNs, kStepNs);
    const DriveOutputs b = reference.step(reference_state, in, k * kStepNs, kStepNs);
    for (std::size_t j = 0; j < 3; ++j) {
      c.position_m.add(a.position_m[j], b.position_m[j]);
      c.linear_velocity_mps.add(a.linear_velocity_mps[j], b.linear_velocity_mps[j]);
      c.angular_velocity_radps.add(a.angular_velocity_radps[j], b.angular_velocity_radps[j]);
    }
    for (std::size_t j = 0; j < 4; ++j) c.orientation.add(a.orientation_wxyz[j], b.orientation_wxyz[j]);
    EXPECT_EQ(a.wheels.size(), b.wheels.size());
    for (std::size_t i = 0; i < std::min(a.wheels.size(), b.wheels.size()); ++i) {
      c.normal_force_n.add(a.wheels[i].normal_force_n, b.wheels[i].normal_force_n);
      c.slip_mps.add(a.wheels[i].slip_mps, b.wheels[i].slip_mps);
      c.steering_rad.add(a.wheels[i].steering_rad, b.wheels[i].steering_rad);
      c.wheel_speed_radps.add(a.wheels[i].wheel_speed_radps, b.wheels[i].wheel_speed_radps);
      c.largest_normal_force_n = std::max(c.largest_normal_force_n, b.wheels[i].normal_force_n);
    }
    c.fell_differs += a.fell != b.fell ? 1 : 0;
    c.fell = b.fell;
  }
  for (const Compared* q : c.all()) {
    std::printf("  %-26s largest difference %.2e of scale %.3g (relative %.1e)\n", q->name, q->difference, q->scale,
                q->relative());
  }
  return c;
}

void expectSame(const Comparison& c) {
  for (const Compared* q : c.all()) {
    EXPECT_LE(q->relative(), kRelativeTolerance)
        << q->name << ": the backends differ by " << q->difference << " at a scale of " << q->scale;
  }
  EXPECT_EQ(c.fell_differs, 0) << "steps where only one backend had fallen";
}

TEST(DriveBackends, AtRestOnAVerticalWall) {
  const auto c = compare(10.5, [](double) { return adhesion(2200.0); });
  expectSame(c);
  EXPECT_GT(c.largest_normal_force_n, 500.0) << "the wheels should carry the adhesion";
  EXPECT_FALSE(c.fell);
  // Two different computations (Simbody's contact subsystem is really in use): equal to
  // round-off, not bit for bit.
  EXPECT_GT(c.normal_force_n.difference, 0.0);
}

TEST(DriveBackends, DrivingUpAndDown) {
  for (const double vy : {0.05, -0.05}) {
    const auto c = compare(4.0, [vy](double) {
      auto in = adhesion(2200.0);
      in.command.vy_mps = vy;
      return in;
    });
    expectSame(c);
    EXPECT_GT(c.slip_mps.scale, 0.0);
  }
}

TEST(DriveBackends, ASquarePath) {
  expectSame(compare(12.0, [](double t) {
    auto in = adhesion(2200.0);
    const int leg = std::min(3, static_cast<int>(t / 3.0));
    const double vx[4] = {0.0, -0.05, 0.0, 0.05};
    const double vy[4] = {0.05, 0.0, -0.05, 0.0};
    in.command.vx_mps = vx[leg];
    in.command.vy_mps = vy[leg];
    return in;
  }));
}

TEST(DriveBackends, APureRotation) {
  expectSame(compare(4.0, [](double) {
    auto in = adhesion(2200.0);
    in.command.wz_radps = 0.3;
    return in;
  }));
}

TEST(DriveBackends, OnAFloorWithoutAdhesion) {
  const auto c = compare(
      3.0,
      [](double) {
        DriveInputs in;
        in.command.vx_mps = 0.1;
        return in;
      },
      WallOrientation::floor());
  expectSame(c);
  EXPECT_GT(c.largest_normal_force_n, 100.0) << "the weight should rest on the wheels";
}

TEST(DriveBackends, AVaryingAdhesionOffCentreWhileDriving) {
  // P_F off the centre puts the adhesion's moment to the test, which the scenarios above
  // (P_F at the centre) leave out; the schedule of drive_model_test's determinism test.
  const auto c = compare(2.0, [](double t) {
    DriveInputs in;
    in.downforce_n = 1500.0 + 500.0 * std::sin(t);
    in.pf_x_m = 0.1;
    in.pf_y_m = -0.05;
    in.command.vx_mps = t < 1.0 ? 0.05 : -0.02;
    in.command.wz_radps = 0.1;
    return in;
  });
  expectSame(c);
  EXPECT_GT(c.largest_normal_force_n, 800.0);
}

TEST(DriveBackends, FallingWithoutAdhesion) {
  const auto c = compare(1.0, [](double) { return adhesion(0.0); });
  expectSame(c);
  EXPECT_TRUE(c.fell);
}

TEST(DriveBackends, FixedWheelsAndACasterDrivingAndTurning) {
  // The differential drive (two fixed wheels, a caster) and the skid-steered grid: welded
  // steering bodies, a freely swivelling and spinning caster with its trail.
  for (const char* robot : {"single-chamber", "grid-2x2"}) {
    const auto c = compare(
        3.0,
        [](double t) {
          auto in = adhesion(600.0);
          in.command.vx_mps = t < 1.5 ? 0.05 : 0.0;
          in.command.wz_radps = t < 1.5 ? 0.0 : 0.3;
          return in;
        },
        WallOrientation::vertical(), robot);
    expectSame(c);
    EXPECT_FALSE(c.fell) << robot;
    EXPECT_GT(c.wheel_speed_radps.difference, 0.0) << robot;
  }
}

TEST(DriveBackends, TheBackendNamesParseAndAnUnknownOneIsNamed) {
  EXPECT_EQ(parseContactBackend("--contact", "direct"), ContactBackend::kDirect);
  EXPECT_EQ(parseContactBackend("--contact", "simbody"), ContactBackend::kSimbody);
  EXPECT_STREQ(toString(ContactBackend::kSimbody), "simbody");
  EXPECT_EQ(DriveParams{}.contact_backend, ContactBackend::kDirect);
  try {
    parseContactBackend("--contact", "bullet");
    FAIL() << "no error for an unknown backend";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--contact = 'bullet'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace climbsim::drive
