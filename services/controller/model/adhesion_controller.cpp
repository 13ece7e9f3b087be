#include "adhesion_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::controller {
namespace {

void requirePositive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ConfigError("adhesion controller: " + std::string(field) + " = " + std::to_string(value) +
                      " (must be finite and > 0)");
  }
}

}  // namespace

AdhesionControllerParams adhesionControllerParamsFromRobot(const RobotDescription& robot,
                                                           const RobotGeometry& geometry) {
  if (static_cast<int>(geometry.chambers.size()) != kValveCount) {
    throw ConfigError("robot " + robot.name + ": chambers.outer_count = " + std::to_string(geometry.outer_count) +
                      " (the adhesion controller commands " + std::to_string(kValveCount - 1) +
                      " ring chambers and the centre)");
  }
  AdhesionControllerParams p;
  p.ambient_pressure_pa = robot.gas.ambient_pressure_pa;
  for (int i = 0; i < kValveCount; ++i) {
    p.chamber_area_m2[i] = geometry.chambers[i].area_m2;
    p.p_RobotChamber_m[i] = {geometry.chambers[i].p_RobotCentroid.x_m, geometry.chambers[i].p_RobotCentroid.y_m};
  }
  p.desired_downforce_n = robot.adhesion.desired_downforce_n;
  p.max_suction_pa = robot.engines.dp_max_pa;
  return p;
}

AdhesionController::AdhesionController(AdhesionControllerParams params) : params_(params) {
  requirePositive("ambient_pressure_pa", params_.ambient_pressure_pa);
  for (int i = 0; i < kValveCount; ++i) {
    requirePositive(("chamber_area_m2[" + std::to_string(i) + "]").c_str(), params_.chamber_area_m2[i]);
    for (double c : params_.p_RobotChamber_m[i]) {
      if (!std::isfinite(c)) throw ConfigError("adhesion controller: chamber centroid " + std::to_string(i + 1) + " is not finite");
    }
  }
  requirePositive("desired_downforce_n", params_.desired_downforce_n);
  requirePositive("max_suction_pa", params_.max_suction_pa);
  requirePositive("force_tau_s", params_.force_tau_s);
  requirePositive("balance_tau_s", params_.balance_tau_s);
  requirePositive("valve_gain_per_pa_s", params_.valve_gain_per_pa_s);
  if (!(params_.reservoir_tracking_ratio > 0.0 && params_.reservoir_tracking_ratio < 1.0)) {
    throw ConfigError("adhesion controller: reservoir_tracking_ratio = " + std::to_string(params_.reservoir_tracking_ratio) +
                      " (must be in (0, 1))");
  }
  if (!(params_.max_trim >= 0.0 && params_.max_trim < 1.0)) {
    throw ConfigError("adhesion controller: max_trim = " + std::to_string(params_.max_trim) + " (must be in [0, 1))");
  }
  for (double a : params_.chamber_area_m2) total_area_m2_ += a;
  // The uniform suction that gives F*: where the force loop starts.
  s_base_pa_ = std::clamp(params_.desired_downforce_n / total_area_m2_, 0.0, params_.max_suction_pa);
}

void AdhesionController::setDesiredDownforce(double downforce_n) {
  requirePositive("desired_downforce_n", downforce_n);
  // Keep what the integral learnt (the leaks), shift it by the change of set-point.
  s_base_pa_ = std::clamp(s_base_pa_ + (downforce_n - params_.desired_downforce_n) / total_area_m2_, 0.0,
                          params_.max_suction_pa);
  params_.desired_downforce_n = downforce_n;
}

std::array<double, kValveCount> AdhesionController::step(const AdhesionMeasurement& m, double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) throw std::invalid_argument("adhesion controller: dt_s must be finite and > 0");
  bool finite = std::isfinite(m.downforce_n) && std::isfinite(m.p_RobotPF_m[0]) && std::isfinite(m.p_RobotPF_m[1]);
  for (double p : m.pressure_pa) finite = finite && std::isfinite(p);
  if (!finite) throw std::invalid_argument("adhesion controller: measurement is not finite");

  const double reservoir_suction_pa = params_.ambient_pressure_pa - m.pressure_pa[kValveCount];
  const double force_error_n = params_.desired_downforce_n - m.downforce_n;
  // Asking the chambers for more suction than the reservoir holds cannot help (engines spinning
  // up, or out of reach): the force loop then holds instead of winding up.
  if (!(force_error_n > 0.0 && reservoir_suction_pa <= s_base_pa_)) {
    s_base_pa_ = std::clamp(s_base_pa_ + dt_s * force_error_n / (total_area_m2_ * params_.force_tau_s), 0.0,
                            params_.max_suction_pa);
  }

  for (int i = 0; i < kValveCount; ++i) {
    const auto& c = params_.p_RobotChamber_m[i];
    const double r_m = std::hypot(c[0], c[1]);
    // The centre chamber's centroid is the origin: it has no side to trim.
    if (params_.balance && r_m > 1e-9) {
      const double towards = (m.p_RobotPF_m[0] * c[0] + m.p_RobotPF_m[1] * c[1]) / (r_m * r_m);
      // A fully open valve cannot pull harder: raising its target further only winds the trim up.
      const bool saturated = opening_[i] >= 1.0 && towards < 0.0;
      if (!saturated) {
        trim_[i] = std::clamp(trim_[i] + dt_s * towards / params_.balance_tau_s, -params_.max_trim, params_.max_trim);
      }
    } else {
      trim_[i] = 0.0;
    }
    // A chamber cannot get deeper than the reservoir: aiming at a fraction of it keeps the valve
    // loop from winding up while the engines spin up (it then tracks the reservoir instead).
    const double target_pa =
        std::min(s_base_pa_ * (1.0 - trim_[i]), params_.reservoir_tracking_ratio * reservoir_suction_pa);
    const double suction_pa = params_.ambient_pressure_pa - m.pressure_pa[i];
    opening_[i] = std::clamp(opening_[i] + dt_s * params_.valve_gain_per_pa_s * (target_pa - suction_pa), 0.0, 1.0);
  }
  return opening_;
}

}  // namespace climbsim::controller
