#include "drive_command.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace climbsim::drive {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Below this contact speed [m/s] a heading is meaningless (atan2 of noise).
constexpr double kStandstillMps = 1e-9;

std::string fmt(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

}  // namespace

double wheelSurfaceSpeed(const WheelMount& wheel, const DriveCommand& c) {
  return std::hypot(c.vx_mps - c.wz_radps * wheel.y_m, c.vy_mps + c.wz_radps * wheel.x_m);
}

std::string checkCommand(const DriveParams& p, const DriveCommand& c) {
  if (!c.wheelMode()) {
    if (!std::isfinite(c.vx_mps)) return "vx_mps = " + fmt(c.vx_mps) + " (must be finite)";
    if (!std::isfinite(c.vy_mps)) return "vy_mps = " + fmt(c.vy_mps) + " (must be finite)";
    if (!std::isfinite(c.wz_radps)) return "wz_radps = " + fmt(c.wz_radps) + " (must be finite)";
    const double absurd = kAbsurdLimitFactor * p.max_speed_mps;
    for (std::size_t i = 0; i < p.wheels.size(); ++i) {
      const double v = wheelSurfaceSpeed(p.wheels[i], c);
      if (!(v <= absurd)) {
        return "(vx_mps, vy_mps, wz_radps) = (" + fmt(c.vx_mps) + ", " + fmt(c.vy_mps) + ", " + fmt(c.wz_radps) +
               ") asks wheel " + std::to_string(i + 1) + " for " + fmt(v) + " m/s (absurd above " + fmt(absurd) +
               ")";
      }
    }
    return {};
  }
  const std::size_t n = p.wheels.size();
  if (c.steering_rad.size() != n || c.wheel_speed_radps.size() != n) {
    return "per-wheel command with " + std::to_string(c.steering_rad.size()) + " steering angles and " +
           std::to_string(c.wheel_speed_radps.size()) + " wheel speeds (the robot has " + std::to_string(n) +
           " wheels)";
  }
  const double absurd_speed = kAbsurdLimitFactor * p.max_speed_mps / p.wheel_radius_m;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = c.steering_rad[i];
    const double w = c.wheel_speed_radps[i];
    if (!(std::isfinite(s) && std::fabs(s) <= 4.0 * kPi)) {
      return "steering_rad[" + std::to_string(i) + "] = " + fmt(s) + " (must be finite, |.| <= 4 pi)";
    }
    if (!(std::isfinite(w) && std::fabs(w) <= absurd_speed)) {
      return "wheel_speed_radps[" + std::to_string(i) + "] = " + fmt(w) + " (must be finite, |.| <= " +
             fmt(absurd_speed) + ")";
    }
  }
  return {};
}

std::vector<WheelSetpoint> wheelTargets(const DriveParams& p, const DriveCommand& c,
                                        const std::vector<WheelSetpoint>& previous) {
  const std::size_t n = p.wheels.size();
  std::vector<WheelSetpoint> out(n);
  const double max_spin = p.max_speed_mps / p.wheel_radius_m;
  if (c.wheelMode()) {
    for (std::size_t i = 0; i < n; ++i) {
      out[i].steering_rad = c.steering_rad[i];
      out[i].wheel_speed_radps = std::clamp(c.wheel_speed_radps[i], -max_spin, max_spin);
    }
    return out;
  }
  double fastest = 0.0;
  for (const auto& w : p.wheels) fastest = std::max(fastest, wheelSurfaceSpeed(w, c));
  const double scale = fastest > p.max_speed_mps ? p.max_speed_mps / fastest : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double prev = i < previous.size() ? previous[i].steering_rad : 0.0;
    const double vx = scale * (c.vx_mps - c.wz_radps * p.wheels[i].y_m);
    const double vy = scale * (c.vy_mps + c.wz_radps * p.wheels[i].x_m);
    const double speed = std::hypot(vx, vy);
    if (speed < kStandstillMps) {
      out[i] = {prev, 0.0};
      continue;
    }
    const double turn = std::remainder(std::atan2(vy, vx) - prev, 2.0 * kPi);  // in [-π, π]
    if (std::fabs(turn) <= kPi / 2.0) {
      out[i] = {prev + turn, speed / p.wheel_radius_m};
    } else {
      out[i] = {prev + turn - std::copysign(kPi, turn), -speed / p.wheel_radius_m};
    }
  }
  return out;
}

}  // namespace climbsim::drive
