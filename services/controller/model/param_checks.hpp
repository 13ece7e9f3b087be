#pragma once
/// @file
/// Range checks of a controller's parameters: ConfigError "<who>: <field> = <value> (must be ...)".

#include <cmath>
#include <string>

#include "climbsim/errors.hpp"

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

}  // namespace climbsim::controller
