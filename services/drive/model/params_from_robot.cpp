#include "params_from_robot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::drive {
namespace {

/// Penetration of each wheel when the wheels share the desired downforce equally [m].
constexpr double kNominalPenetrationM = 1.0e-3;

WheelKind kindOf(RobotDescription::WheelKind kind) {
  switch (kind) {
    case RobotDescription::WheelKind::kFixed: return WheelKind::kFixed;
    case RobotDescription::WheelKind::kCaster: return WheelKind::kCaster;
    case RobotDescription::WheelKind::kSteerable: break;
  }
  return WheelKind::kSteerable;
}

}  // namespace

double chassisMass(const DriveParams& p) {
  const double n = static_cast<double>(p.wheels.size());
  return p.mass_kg * (1.0 - n * p.unit_mass_fraction);
}

void setDiscInertia(DriveParams& p) {
  const double chassis_mass_kg = chassisMass(p);
  const double r2 = p.body_radius_m * p.body_radius_m;
  const double thickness_m = 2.0 * p.com_height_m;
  p.inertia_xx_kgm2 = chassis_mass_kg * (r2 / 4.0 + thickness_m * thickness_m / 12.0);
  p.inertia_yy_kgm2 = p.inertia_xx_kgm2;
  p.inertia_zz_kgm2 = chassis_mass_kg * r2 / 2.0;
}

void setBoxInertia(DriveParams& p, double length_m, double width_m) {
  const double m = chassisMass(p);
  const double t2 = 4.0 * p.com_height_m * p.com_height_m;
  p.inertia_xx_kgm2 = m * (width_m * width_m + t2) / 12.0;
  p.inertia_yy_kgm2 = m * (length_m * length_m + t2) / 12.0;
  p.inertia_zz_kgm2 = m * (length_m * length_m + width_m * width_m) / 12.0;
}

DriveParams driveParamsFromRobot(const RobotDescription& d, const RobotGeometry& geometry) {
  validateRobotDescription(d, "robot " + d.name);
  DriveParams p;
  p.mass_kg = d.body.mass_kg;
  p.com_height_m = d.body.com_height_m;
  p.body_radius_m = d.body.outerRadius();
  p.wheels.clear();
  for (const auto& w : geometry.wheels) {
    WheelMount mount{w.p_RobotWheel.x_m, w.p_RobotWheel.y_m, kindOf(w.kind), w.radius_m, w.friction_coefficient,
                     w.radius_m, 0.0};
    if (mount.kind == WheelKind::kCaster) mount.trail_m = w.radius_m;
    p.wheels.push_back(mount);
  }
  if (std::none_of(p.wheels.begin(), p.wheels.end(), [](const WheelMount& w) { return isDriven(w.kind); })) {
    throw ConfigError("robot " + d.name + ": wheels: every wheel is a caster: the robot needs a driven wheel "
                      "(steerable or fixed)");
  }
  p.max_speed_mps = d.drive.max_speed_mps;
  p.max_steering_rate_radps = d.drive.max_steering_rate_radps;

  const double n = static_cast<double>(p.wheels.size());
  const double nominal_load_n = d.adhesion.desired_downforce_n / n;
  double smallest_radius_m = p.wheels.front().radius_m;
  for (const auto& w : p.wheels) smallest_radius_m = std::min(smallest_radius_m, w.radius_m);
  p.contact.hertz_modulus_pa =
      nominal_load_n / ((4.0 / 3.0) * std::sqrt(smallest_radius_m) * std::pow(kNominalPenetrationM, 1.5));
  p.tyre_patch_m = 2.0 * std::sqrt(2.0 * smallest_radius_m * kNominalPenetrationM);
  p.wheel_servo.torque_max_nm = 0.0;
  for (const auto& w : p.wheels) {
    if (!isDriven(w.kind)) continue;
    p.wheel_servo.torque_max_nm =
        std::max(p.wheel_servo.torque_max_nm, w.friction_coefficient * nominal_load_n * w.radius_m);
  }
  if (d.body.shape == RobotDescription::Shape::kRectangle) {
    setBoxInertia(p, d.body.length_m, d.body.width_m);
  } else {
    setDiscInertia(p);
  }
  validateDriveParams(p);
  return p;
}

}  // namespace climbsim::drive
