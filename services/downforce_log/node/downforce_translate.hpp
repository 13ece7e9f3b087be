#pragma once
/// @file
/// thermo/AdhesionForce as the downforce log's model input.

#include "downforce_log.hpp"
#include "thermo.h"

namespace climbsim::downforce_log {

/// F and the set-point of one AdhesionForce sample.
inline DownforceLogInputs inputsFromIdl(const AdhesionForce& sample) {
  return {sample.downforce_n(), sample.downforce_setpoint_n()};
}

}  // namespace climbsim::downforce_log
