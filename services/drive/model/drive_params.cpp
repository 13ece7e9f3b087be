#include "drive_params.hpp"

#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::drive {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string fmt(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

/// "" or "<key> = <value>: <why>".
std::string require(bool ok, const std::string& key, double value, const char* why) {
  return ok ? std::string() : key + " = " + fmt(value) + ": " + why;
}

}  // namespace

std::string checkDriveParams(const DriveParams& p) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  struct Check {
    const char* key;
    double value;
    bool ok;
    const char* why;
  };
  const Check checks[] = {
      {"mass_kg", p.mass_kg, positive(p.mass_kg), "must be > 0"},
      {"com_height_m", p.com_height_m, positive(p.com_height_m), "must be > 0"},
      {"body_radius_m", p.body_radius_m, positive(p.body_radius_m), "must be > 0"},
      {"inertia_xx_kgm2", p.inertia_xx_kgm2, positive(p.inertia_xx_kgm2), "must be > 0"},
      {"inertia_yy_kgm2", p.inertia_yy_kgm2, positive(p.inertia_yy_kgm2), "must be > 0"},
      {"inertia_zz_kgm2", p.inertia_zz_kgm2, positive(p.inertia_zz_kgm2), "must be > 0"},
      {"wheel_spin_inertia_kgm2", p.wheel_spin_inertia_kgm2, positive(p.wheel_spin_inertia_kgm2), "must be > 0"},
      {"steering_inertia_kgm2", p.steering_inertia_kgm2, positive(p.steering_inertia_kgm2), "must be > 0"},
      {"caster_inertia_kgm2", p.caster_inertia_kgm2, positive(p.caster_inertia_kgm2), "must be > 0"},
      {"caster_damping_nmsprad", p.caster_damping_nmsprad, non_negative(p.caster_damping_nmsprad), "must be >= 0"},
      {"contact.hertz_modulus_pa", p.contact.hertz_modulus_pa, positive(p.contact.hertz_modulus_pa), "must be > 0"},
      {"contact.dissipation_spm", p.contact.dissipation_spm, non_negative(p.contact.dissipation_spm),
       "must be >= 0"},
      {"contact.tangential_stiffness_npm", p.contact.tangential_stiffness_npm,
       positive(p.contact.tangential_stiffness_npm), "must be > 0"},
      {"contact.tangential_damping_nspm", p.contact.tangential_damping_nspm,
       non_negative(p.contact.tangential_damping_nspm), "must be >= 0"},
      {"wheel_servo.kp_nmprad", p.wheel_servo.kp_nmprad, positive(p.wheel_servo.kp_nmprad), "must be > 0"},
      {"wheel_servo.kd_nmsprad", p.wheel_servo.kd_nmsprad, non_negative(p.wheel_servo.kd_nmsprad), "must be >= 0"},
      {"wheel_servo.torque_max_nm", p.wheel_servo.torque_max_nm, positive(p.wheel_servo.torque_max_nm),
       "must be > 0"},
      {"steering_servo.kp_nmprad", p.steering_servo.kp_nmprad, positive(p.steering_servo.kp_nmprad), "must be > 0"},
      {"steering_servo.kd_nmsprad", p.steering_servo.kd_nmsprad, non_negative(p.steering_servo.kd_nmsprad),
       "must be >= 0"},
      {"steering_servo.torque_max_nm", p.steering_servo.torque_max_nm, positive(p.steering_servo.torque_max_nm),
       "must be > 0"},
      {"max_steering_rate_radps", p.max_steering_rate_radps, positive(p.max_steering_rate_radps), "must be > 0"},
      {"command_delay_s", p.command_delay_s, non_negative(p.command_delay_s) && p.command_delay_s <= 1.0,
       "must be in [0, 1]"},
      {"max_speed_mps", p.max_speed_mps, positive(p.max_speed_mps), "must be > 0"},
      {"sealing_drag_coefficient", p.sealing_drag_coefficient, non_negative(p.sealing_drag_coefficient),
       "must be >= 0"},
      {"drag_regularisation_mps", p.drag_regularisation_mps, positive(p.drag_regularisation_mps), "must be > 0"},
      {"gravity_mps2", p.gravity_mps2, positive(p.gravity_mps2), "must be > 0"},
      {"substep_s", p.substep_s, positive(p.substep_s) && p.substep_s <= 0.01, "must be in (0, 0.01]"},
      {"fall_distance_m", p.fall_distance_m, positive(p.fall_distance_m), "must be > 0"},
      {"fall_contact_loss_s", p.fall_contact_loss_s, positive(p.fall_contact_loss_s), "must be > 0"},
      {"fall_speed_mps", p.fall_speed_mps, positive(p.fall_speed_mps), "must be > 0"},
  };
  for (const auto& c : checks) {
    if (const auto why = require(c.ok, c.key, c.value, c.why); !why.empty()) return why;
  }
  const double n = static_cast<double>(p.wheels.size());
  if (p.wheels.empty() || p.wheels.size() > 8) {
    return "wheels: " + std::to_string(p.wheels.size()) + " drive units (must be 1..8)";
  }
  if (!(std::isfinite(p.unit_mass_fraction) && p.unit_mass_fraction > 0.0 && p.unit_mass_fraction * n < 0.5)) {
    return require(false, "unit_mass_fraction", p.unit_mass_fraction, "must be > 0 and below 0.5 / wheel count");
  }
  for (std::size_t i = 0; i < p.wheels.size(); ++i) {
    const auto& w = p.wheels[i];
    const std::string key = "wheels[" + std::to_string(i) + "]";
    const bool caster = w.kind == WheelKind::kCaster;
    const Check unit[] = {
        {"radius_m", w.radius_m, positive(w.radius_m), "must be > 0"},
        {"friction_coefficient", w.friction_coefficient, positive(w.friction_coefficient), "must be > 0"},
        {"relaxation_length_m", w.relaxation_length_m, positive(w.relaxation_length_m), "must be > 0"},
        {"trail_m", w.trail_m, caster ? non_negative(w.trail_m) : w.trail_m == 0.0,
         caster ? "must be >= 0" : "must be 0 (only a caster trails)"},
    };
    for (const auto& c : unit) {
      if (const auto why = require(c.ok, key + "." + c.key, c.value, c.why); !why.empty()) return why;
    }
    const double r = std::hypot(w.x_m, w.y_m);
    if (!(std::isfinite(r) && r + w.trail_m + w.radius_m <= p.body_radius_m)) {
      return key + ": mount at radius " + fmt(r) +
             " m: the wheel must lie inside the body (radius + trail_m + radius_m <= body_radius_m)";
    }
  }
  return {};
}

void validateDriveParams(const DriveParams& params) {
  const std::string why = checkDriveParams(params);
  if (!why.empty()) throw ConfigError("drive parameters: " + why);
}

const char* toString(WheelKind kind) {
  switch (kind) {
    case WheelKind::kFixed: return "fixed";
    case WheelKind::kCaster: return "caster";
    case WheelKind::kSteerable: break;
  }
  return "steerable";
}

const char* toString(ContactBackend backend) {
  return backend == ContactBackend::kSimbody ? "simbody" : "direct";
}

ContactBackend parseContactBackend(const std::string& what, const std::string& text) {
  if (text == "direct") return ContactBackend::kDirect;
  if (text == "simbody") return ContactBackend::kSimbody;
  throw ConfigError(what + " = '" + text + "': expected direct or simbody");
}

WallOrientation WallOrientation::overhang(double overhang_deg) {
  const double a = overhang_deg * kPi / 180.0;
  return {0.0, -std::cos(a), std::sin(a)};
}

WallOrientation WallOrientation::parse(const std::string& what, const std::string& text) {
  if (text == "vertical") return vertical();
  if (text == "floor") return floor();
  if (text == "ceiling") return overhang(90.0);
  const std::string prefix = "overhang:";
  if (text.rfind(prefix, 0) == 0) {
    const std::string number = text.substr(prefix.size());
    std::size_t used = 0;
    double deg = 0.0;
    try {
      deg = std::stod(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == number.size() && !number.empty() && std::isfinite(deg) && std::fabs(deg) <= 180.0) {
      return overhang(deg);
    }
  }
  throw ConfigError(what + " = '" + text +
                    "': expected vertical, floor, ceiling or overhang:DEG (degrees beyond vertical, -180..180)");
}

}  // namespace climbsim::drive
