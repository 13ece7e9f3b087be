// The drive's wheels on the scene's surface (docs/design.md#drive): a step of known height
// under one wheel, on a flat wall of several orientations, against the statics of the rigid
// robot on Hertz contacts solved here independently of the model; the level wall gives the
// wall plane's numbers exactly; a wheel over a hole loses its contact.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <vector>

#include "drive_model.hpp"
#include "params_from_robot.hpp"
#include "rectangle_mesh.hpp"
#include "wheel_ground.hpp"

namespace climbsim::drive {
namespace {

constexpr std::int64_t kStepNs = 5'000'000;
constexpr double kDownforceN = 2200.0;

DriveParams robot(const char* name) {
  const auto description = loadRobotDescription(std::string(CLIMBSIM_ROBOTS_DIR) + "/" + name + ".yaml");
  return driveParamsFromRobot(description, computeGeometry(description));
}

/// A flat wall around the origin with a square plateau `step_m` high (0: none) of side 0.12 m
/// centred under (step_x, step_y), or a square hole of that side (step_m < 0: no surface).
std::shared_ptr<const WheelGround> wallWithStep(double step_x, double step_y, double step_m) {
  scene::TriangleMesh mesh;
  const double a = 0.06;
  if (step_m >= 0.0) {
    scene::addRectangle(mesh, -1.0, 1.0, -1.0, 1.0, 0.0);
    if (step_m > 0.0) scene::addRectangle(mesh, step_x - a, step_x + a, step_y - a, step_y + a, step_m);
  } else {  // the wall around a hole: four squares
    scene::addRectangle(mesh, -1.0, step_x - a, -1.0, 1.0, 0.0);
    scene::addRectangle(mesh, step_x + a, 1.0, -1.0, 1.0, 0.0);
    scene::addRectangle(mesh, step_x - a, step_x + a, -1.0, step_y - a, 0.0);
    scene::addRectangle(mesh, step_x - a, step_x + a, step_y + a, 1.0, 0.0);
  }
  return std::make_shared<const WheelGround>(scene::SurfaceHeights(std::move(mesh), 0.05));
}

/// The model at rest: held for 1 s while F builds, then released and left for 4 s.
DriveOutputs settle(const DriveParams& params, const WallOrientation& wall) {
  const DriveModel model(params, wall);
  DriveModelState state = model.initialState(StartPose{});
  DriveOutputs out;
  for (std::int64_t k = 0; k < 1000; ++k) {
    DriveInputs in;
    in.downforce_n = kDownforceN;
    in.held = k < 200;
    out = model.step(state, in, k * kStepNs, kStepNs);
  }
  return out;
}

/// The statics of the rigid robot at rest, solved independently of the model: unknowns the
/// height z0 of R's origin and the tilt a = (a_x, a_y) (R = rotation by |a| about a, R's
/// axes W's at a = 0); wheel i's centre c_i = o + R (x_i - trail_i, y_i, r_i), its load
/// N_i = (4/3) E sqrt(r) d_i^1.5 with d_i = h_i + r_i - c_i,z on the surface height h_i under
/// it, acting along W's z at (c_i,x, c_i,y, h_i). Balance along W's z and about W's x and y
/// at o of: the loads, the adhesion -F z_W at o, the weight m g at the centre of mass (R's
/// (x_m, y_m, com_height_m)) and the in-plane friction that carries the weight's in-plane part,
/// shared in proportion to the loads, at the contact points.
struct Statics {
  std::vector<double> loads_n;
  Eigen::Vector3d body_z;  ///< R's z in W
};

Statics solveStatics(const DriveParams& p, const WallOrientation& wall, const std::vector<double>& heights) {
  const std::size_t n = p.wheels.size();
  const double m_half = 0.5 * p.mass_kg * p.unit_mass_fraction;
  Eigen::Vector3d com_R(0.0, 0.0, p.com_height_m);
  for (const auto& w : p.wheels) com_R += m_half * Eigen::Vector3d(2.0 * w.x_m - w.trail_m, 2.0 * w.y_m, 0.0) / p.mass_kg;
  const Eigen::Vector3d weight = p.mass_kg * p.gravity_mps2 * Eigen::Vector3d(wall.gravity_x, wall.gravity_y, wall.gravity_z);
  struct Result {
    Eigen::Vector3d residual;
    Statics statics;
  };
  const auto evaluate = [&](const Eigen::Vector3d& u) {
    const Eigen::Vector3d a(u[1], u[2], 0.0);
    const Eigen::Matrix3d R =
        a.norm() > 0.0 ? Eigen::AngleAxisd(a.norm(), a.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d o(0.0, 0.0, u[0]);
    Result r;
    r.statics.loads_n.resize(n);
    r.statics.body_z = R.col(2);
    std::vector<Eigen::Vector3d> points(n);
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& w = p.wheels[i];
      const Eigen::Vector3d c = o + R * Eigen::Vector3d(w.x_m - w.trail_m, w.y_m, w.radius_m);
      const double d = heights[i] + w.radius_m - c.z();
      r.statics.loads_n[i] = d > 0.0 ? (4.0 / 3.0) * p.contact.hertz_modulus_pa * std::sqrt(w.radius_m) * std::pow(d, 1.5) : 0.0;
      points[i] = Eigen::Vector3d(c.x(), c.y(), heights[i]);
      total += r.statics.loads_n[i];
    }
    Eigen::Vector3d force = Eigen::Vector3d(0, 0, -kDownforceN) + weight;
    Eigen::Vector3d moment = (R * com_R).cross(weight);
    const Eigen::Vector3d in_plane(weight.x(), weight.y(), 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d f = Eigen::Vector3d(0, 0, r.statics.loads_n[i]) - in_plane * (r.statics.loads_n[i] / total);
      force += f;
      moment += (points[i] - o).cross(f);
    }
    r.residual = Eigen::Vector3d(force.z(), moment.x(), moment.y());
    return r;
  };
  Eigen::Vector3d u(p.wheels.front().radius_m * 0.0, 0.0, 0.0);
  u[0] = -0.001;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const Result here = evaluate(u);
    Eigen::Matrix3d jacobian;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d du = Eigen::Vector3d::Zero();
      du[k] = 1e-8;
      jacobian.col(k) = (evaluate(u + du).residual - here.residual) / 1e-8;
    }
    u -= jacobian.fullPivLu().solve(here.residual);
  }
  EXPECT_LT(evaluate(u).residual.norm(), 1e-6);
  return evaluate(u).statics;
}

Eigen::Vector3d bodyZ(const DriveOutputs& out) {
  const auto& q = out.orientation_wxyz;
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix().col(2);
}

struct StepCase {
  const char* name;
  WallOrientation wall;
  double step_m;
  const char* robot = "cromsci";
};

class WheelOnStep : public ::testing::TestWithParam<StepCase> {};

TEST_P(WheelOnStep, TiltAndLoadsAgreeWithTheStaticsWithinTwoPercent) {
  DriveParams params = robot(GetParam().robot);
  const WheelMount& first = params.wheels.front();
  params.ground = wallWithStep(first.x_m - first.trail_m, first.y_m, GetParam().step_m);
  const DriveOutputs out = settle(params, GetParam().wall);
  ASSERT_FALSE(out.fell);
  std::vector<double> heights(params.wheels.size(), 0.0);
  heights.front() = GetParam().step_m;
  const Statics statics = solveStatics(params, GetParam().wall, heights);
  const Eigen::Vector3d tilt_sim = bodyZ(out) - Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tilt_statics = statics.body_z - Eigen::Vector3d::UnitZ();
  std::printf("%s: tilt %.5f rad (statics %.5f rad)", GetParam().name, std::asin(tilt_sim.head<2>().norm()),
              std::asin(tilt_statics.head<2>().norm()));
  EXPECT_LT((tilt_sim - tilt_statics).head<2>().norm(), 0.02 * tilt_statics.head<2>().norm());
  for (std::size_t i = 0; i < statics.loads_n.size(); ++i) {
    std::printf(", N%zu %.1f N (statics %.1f N)", i + 1, out.wheels[i].normal_force_n, statics.loads_n[i]);
    EXPECT_NEAR(out.wheels[i].normal_force_n, statics.loads_n[i], 0.02 * statics.loads_n[i]) << "wheel " << i + 1;
  }
  std::printf("\n");
}

INSTANTIATE_TEST_SUITE_P(
    FlatWall, WheelOnStep,
    ::testing::Values(StepCase{"floor_8mm", WallOrientation::floor(), 0.008},
                      StepCase{"vertical_3mm", WallOrientation::vertical(), 0.003},
                      StepCase{"vertical_8mm", WallOrientation::vertical(), 0.008},
                      StepCase{"overhang30_8mm", WallOrientation::overhang(30.0), 0.008},
                      StepCase{"ceiling_8mm", WallOrientation::overhang(90.0), 0.008},
                      // Four wheels: the step shifts load onto the diagonal through it.
                      StepCase{"grid2x2_floor_0p5mm", WallOrientation::floor(), 0.0005, "grid-2x2"},
                      StepCase{"grid2x2_vertical_0p5mm", WallOrientation::vertical(), 0.0005, "grid-2x2"},
                      StepCase{"grid2x2_vertical_3mm", WallOrientation::vertical(), 0.003, "grid-2x2"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(WheelGround, ALevelWallAtZeroGivesTheWallPlanesNumbers) {
  DriveParams plane = robot("cromsci");
  DriveParams level = plane;
  level.ground = wallWithStep(0.0, 0.0, 0.0);
  const DriveModel a(plane, WallOrientation::vertical()), b(level, WallOrientation::vertical());
  DriveModelState sa = a.initialState(StartPose{0.1, 0.2, 0.3}), sb = b.initialState(StartPose{0.1, 0.2, 0.3});
  for (std::int64_t k = 0; k < 600; ++k) {
    DriveInputs in;
    in.downforce_n = kDownforceN;
    in.held = k < 200;
    in.command.vx_mps = k < 300 ? 0.0 : 0.05;
    const DriveOutputs oa = a.step(sa, in, k * kStepNs, kStepNs), ob = b.step(sb, in, k * kStepNs, kStepNs);
    ASSERT_EQ(oa.position_m, ob.position_m) << "step " << k;
    ASSERT_EQ(oa.orientation_wxyz, ob.orientation_wxyz) << "step " << k;
    for (std::size_t i = 0; i < oa.wheels.size(); ++i) {
      ASSERT_EQ(oa.wheels[i].normal_force_n, ob.wheels[i].normal_force_n) << "step " << k;
      ASSERT_EQ(oa.wheels[i].slip_mps, ob.wheels[i].slip_mps) << "step " << k;
    }
  }
}

TEST(WheelGround, AWheelOverAHoleWiderThanItsFootprintLosesContact) {
  // A 120 mm hole under wheel 1 (footprint 100 mm): the other two wheels and the body hold;
  // wheel 1 hangs in the hole with no load.
  DriveParams params = robot("cromsci");
  const WheelMount& first = params.wheels.front();
  params.ground = wallWithStep(first.x_m - first.trail_m, first.y_m, -1.0);
  const DriveModel model(params, WallOrientation::floor());
  DriveModelState state = model.initialState(StartPose{});
  DriveInputs in;
  in.downforce_n = 300.0;
  in.held = true;
  DriveOutputs out;
  for (std::int64_t k = 0; k < 100; ++k) out = model.step(state, in, k * kStepNs, kStepNs);
  EXPECT_EQ(out.wheels[0].normal_force_n, 0.0);
  EXPECT_GT(out.wheels[1].normal_force_n, 0.0);
  EXPECT_GT(out.wheels[2].normal_force_n, 0.0);
}

TEST(WheelGround, AWheelClimbsAStepEdgeAndTheBodyLiftsOverIt) {
  // Driving along R's x onto an 8 mm plateau under wheel 1's path: wheel 1's contact normal
  // tilts at the edge, the body tilts while wheel 1 is on top.
  DriveParams params = robot("cromsci");
  const WheelMount& first = params.wheels.front();
  params.ground = wallWithStep(first.x_m + 0.10, first.y_m, 0.008);
  const DriveModel model(params, WallOrientation::floor());
  DriveModelState state = model.initialState(StartPose{});
  double most_tilt = 0.0;
  for (std::int64_t k = 0; k < 1200; ++k) {
    DriveInputs in;
    in.downforce_n = 1000.0;
    in.held = k < 100;
    in.command.vx_mps = k < 100 ? 0.0 : 0.05;
    const DriveOutputs out = model.step(state, in, k * kStepNs, kStepNs);
    ASSERT_FALSE(out.fell) << "step " << k;
    most_tilt = std::max(most_tilt, (bodyZ(out) - Eigen::Vector3d::UnitZ()).head<2>().norm());
  }
  // A plane through the wheels with one 8 mm higher tilts by about 8 mm / (1.5 r_mount).
  EXPECT_GT(most_tilt, 0.5 * 0.008 / (1.5 * std::hypot(first.x_m, first.y_m)));
}

}  // namespace
}  // namespace climbsim::drive
