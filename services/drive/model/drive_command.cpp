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

std::string sidewaysNote(const DriveParams& p, const DriveCommand& c) {
  if (c.wheelMode() || c.vy_mps == 0.0) return {};
  std::string fixed;
  for (std::size_t i = 0; i < p.wheels.size(); ++i) {
    if (p.wheels[i].kind == WheelKind::kFixed) fixed += (fixed.empty() ? "" : ", ") + std::to_string(i + 1);
  }
  if (fixed.empty()) return {};
  return "vy_mps = " + fmt(c.vy_mps) + ": fixed wheels (" + fixed +
         ") cannot move sideways; they roll at vx - wz y only and vy is ignored for them";
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
  for (std::size_t i = 0; i < n; ++i) {
    const double absurd_speed = kAbsurdLimitFactor * p.max_speed_mps / p.wheels[i].radius_m;
    const double s = c.steering_rad[i];
    const double w = c.wheel_speed_radps[i];
    const WheelKind kind = p.wheels[i].kind;
    if (!(std::isfinite(s) && std::fabs(s) <= 4.0 * kPi)) {
      return "steering_rad[" + std::to_string(i) + "] = " + fmt(s) + " (must be finite, |.| <= 4 pi)";
    }
    if (!(std::isfinite(w) && std::fabs(w) <= absurd_speed)) {
      return "wheel_speed_radps[" + std::to_string(i) + "] = " + fmt(w) + " (must be finite, |.| <= " +
             fmt(absurd_speed) + ")";
    }
    if (kind != WheelKind::kSteerable && s != 0.0) {
      return "steering_rad[" + std::to_string(i) + "] = " + fmt(s) + " (wheel " + std::to_string(i + 1) + " is " +
             toString(kind) + ": it cannot be steered, send 0)";
    }
    if (kind == WheelKind::kCaster && w != 0.0) {
      return "wheel_speed_radps[" + std::to_string(i) + "] = " + fmt(w) + " (wheel " + std::to_string(i + 1) +
             " is a caster: it is not driven, send 0)";
    }
  }
  return {};
}

std::vector<WheelSetpoint> wheelTargets(const DriveParams& p, const DriveCommand& c,
                                        const std::vector<WheelSetpoint>& previous) {
  const std::size_t n = p.wheels.size();
  std::vector<WheelSetpoint> out(n);
  if (c.wheelMode()) {
    for (std::size_t i = 0; i < n; ++i) {
      const double max_spin = p.max_speed_mps / p.wheels[i].radius_m;
      out[i].steering_rad = c.steering_rad[i];
      out[i].wheel_speed_radps = std::clamp(c.wheel_speed_radps[i], -max_spin, max_spin);
    }
    return out;
  }
  double fastest = 0.0;
  for (const auto& w : p.wheels) {
    if (w.kind == WheelKind::kSteerable) fastest = std::max(fastest, wheelSurfaceSpeed(w, c));
    if (w.kind == WheelKind::kFixed) fastest = std::max(fastest, std::fabs(c.vx_mps - c.wz_radps * w.y_m));
  }
  const double scale = fastest > p.max_speed_mps ? p.max_speed_mps / fastest : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const WheelMount& wheel = p.wheels[i];
    if (wheel.kind == WheelKind::kCaster) continue;
    if (wheel.kind == WheelKind::kFixed) {
      out[i] = {0.0, scale * (c.vx_mps - c.wz_radps * wheel.y_m) / wheel.radius_m};
      continue;
    }
    const double prev = i < previous.size() ? previous[i].steering_rad : 0.0;
    const double vx = scale * (c.vx_mps - c.wz_radps * wheel.y_m);
    const double vy = scale * (c.vy_mps + c.wz_radps * wheel.x_m);
    const double speed = std::hypot(vx, vy);
    if (speed < kStandstillMps) {
      out[i] = {prev, 0.0};
      continue;
    }
    const double turn = std::remainder(std::atan2(vy, vx) - prev, 2.0 * kPi);  // in [-π, π]
    if (std::fabs(turn) <= kPi / 2.0) {
      out[i] = {prev + turn, speed / wheel.radius_m};
    } else {
      out[i] = {prev + turn - std::copysign(kPi, turn), -speed / wheel.radius_m};
    }
  }
  return out;
}

}  // namespace climbsim::drive
