#include "params_from_robot.hpp"

#include <cmath>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::drive {
namespace {

/// Penetration of each wheel when the wheels share the desired downforce equally [m].
constexpr double kNominalPenetrationM = 1.0e-3;

/// The drive units of DriveParams are steerable and driven, all with one wheel radius and one
/// friction coefficient: a robot file with other wheels is refused by name.
void checkWheelsModelled(const RobotDescription& d) {
  const RobotDescription::Wheel& first = d.wheels.front();
  for (std::size_t i = 0; i < d.wheels.size(); ++i) {
    const auto& w = d.wheels[i];
    const std::string key = "robot " + d.name + ": wheels[" + std::to_string(i + 1) + "]";
    if (w.kind != RobotDescription::WheelKind::kSteerable) {
      throw ConfigError(key + ".kind = " + toString(w.kind) + ": the drive model has steerable wheels only");
    }
    if (w.radius_m != first.radius_m || w.friction_coefficient != first.friction_coefficient) {
      throw ConfigError(key + ": the drive model needs every wheel's radius_m and friction_coefficient equal to "
                              "wheels[1]'s");
    }
  }
}

}  // namespace

void setDiscInertia(DriveParams& p) {
  const double n = static_cast<double>(p.wheels.size());
  const double chassis_mass_kg = p.mass_kg * (1.0 - n * p.unit_mass_fraction);
  const double r2 = p.body_radius_m * p.body_radius_m;
  const double thickness_m = 2.0 * p.com_height_m;
  p.inertia_xx_kgm2 = chassis_mass_kg * (r2 / 4.0 + thickness_m * thickness_m / 12.0);
  p.inertia_yy_kgm2 = p.inertia_xx_kgm2;
  p.inertia_zz_kgm2 = chassis_mass_kg * r2 / 2.0;
}

DriveParams driveParamsFromRobot(const RobotDescription& d, const RobotGeometry& geometry) {
  validateRobotDescription(d, "robot " + d.name);
  DriveParams p;
  p.mass_kg = d.body.mass_kg;
  p.com_height_m = d.body.com_height_m;
  checkWheelsModelled(d);
  const RobotDescription::Wheel& wheel = d.wheels.front();
  p.body_radius_m = d.body.outerRadius();
  p.wheel_radius_m = wheel.radius_m;
  p.wheels.clear();
  for (const auto& w : geometry.wheels) p.wheels.push_back({w.p_RobotWheel.x_m, w.p_RobotWheel.y_m});
  p.contact.friction_coefficient = wheel.friction_coefficient;
  p.contact.relaxation_length_m = wheel.radius_m;
  p.max_speed_mps = d.drive.max_speed_mps;
  p.max_steering_rate_radps = d.drive.max_steering_rate_radps;

  const double n = static_cast<double>(p.wheels.size());
  const double nominal_load_n = d.adhesion.desired_downforce_n / n;
  p.contact.hertz_modulus_pa =
      nominal_load_n / ((4.0 / 3.0) * std::sqrt(p.wheel_radius_m) * std::pow(kNominalPenetrationM, 1.5));
  p.wheel_servo.torque_max_nm = p.contact.friction_coefficient * nominal_load_n * p.wheel_radius_m;
  setDiscInertia(p);
  validateDriveParams(p);
  return p;
}

}  // namespace climbsim::drive
