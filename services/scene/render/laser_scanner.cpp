#include "laser_scanner.hpp"

#include <cmath>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::scene {

namespace {

constexpr double kPi = 3.14159265358979323846;

template <typename T>
[[noreturn]] void badValue(const char* key, T value, const char* requirement) {
  std::ostringstream msg;
  msg << "laser scanner: " << key << " = " << value << ": " << requirement;
  throw ConfigError(msg.str());
}

}  // namespace

LaserParams LaserParams::fromScanRange(double scan_angle_range_deg, double angular_resolution_deg,
                                       double max_distance_m) {
  if (!std::isfinite(scan_angle_range_deg) || scan_angle_range_deg <= 0.0 || scan_angle_range_deg > 360.0) {
    badValue("scan_angle_range", scan_angle_range_deg, "must be in (0, 360] degrees");
  }
  if (!std::isfinite(angular_resolution_deg) || angular_resolution_deg <= 0.0) {
    badValue("angular_resolution", angular_resolution_deg, "must be > 0 degrees");
  }
  const double steps = std::floor(scan_angle_range_deg / angular_resolution_deg + 0.01);
  if (steps + 1.0 > kMaxLaserBeams) {
    badValue("angular_resolution", angular_resolution_deg, "gives more than 4096 beams");
  }
  LaserParams p;
  p.angle_min_rad = -0.5 * scan_angle_range_deg * kPi / 180.0;
  p.angle_increment_rad = angular_resolution_deg * kPi / 180.0;
  p.beam_count = static_cast<int>(steps) + 1;
  p.range_max_m = max_distance_m;
  p.validate();
  return p;
}

void LaserParams::validate() const {
  if (!std::isfinite(angle_min_rad)) badValue("angle_min_rad", angle_min_rad, "must be finite");
  if (!std::isfinite(angle_increment_rad) || angle_increment_rad <= 0.0) {
    badValue("angle_increment_rad", angle_increment_rad, "must be > 0");
  }
  if (beam_count < 1 || beam_count > kMaxLaserBeams) badValue("beam_count", beam_count, "must be in 1..4096");
  if (!std::isfinite(range_min_m) || range_min_m < 0.0) badValue("range_min_m", range_min_m, "must be >= 0");
  if (!std::isfinite(range_max_m) || range_max_m <= range_min_m) {
    badValue("range_max_m", range_max_m, "must be finite and > range_min_m");
  }
}

}  // namespace climbsim::scene
