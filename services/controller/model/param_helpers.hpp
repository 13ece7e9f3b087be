#pragma once
/// @file
/// What the controllers' parameters share: range checks (ConfigError "<who>: <field> = <value>
/// (must be ...)") and the chambers' areas and centroids from a robot's geometry.

#include <cmath>
#include <string>

#include "climbsim/errors.hpp"
#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim::controller {

/// ConfigError unless value is finite and > 0.
inline void requirePositive(const char* who, const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ConfigError(std::string(who) + ": " + field + " = " + std::to_string(value) + " (must be finite and > 0)");
  }
}

/// ConfigError unless value is finite and in [lo, hi] (`range` says so in the message).
inline void requireIn(const char* who, const char* field, double value, double lo, double hi, const char* range) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    throw ConfigError(std::string(who) + ": " + field + " = " + std::to_string(value) + " (must be in " + range + ")");
  }
}

/// Appends each chamber's suction area A_i [m²] to p.chamber_area_m2 and its centroid P_i (x, y)
/// [m] to p.p_RobotChamber_m, chambers 1..N in order.
template <class Params>
void addChambers(const RobotGeometry& geometry, Params& p) {
  for (const auto& chamber : geometry.chambers) {
    p.chamber_area_m2.push_back(chamber.area_m2);
    p.p_RobotChamber_m.push_back({chamber.p_RobotCentroid.x_m, chamber.p_RobotCentroid.y_m});
  }
}

}  // namespace climbsim::controller
