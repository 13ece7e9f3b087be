#pragma once
/// @file
/// The words of a fall: what climbsim-drive reports to the clock (and the clock's Stop and
/// summary.json repeat), and what climbsim solo ends its run with.

#include <cstdint>
#include <string>

#include "drive_types.hpp"

namespace climbsim::drive {

/// "FELL at t = T s: the robot left the wall at x = X m, y = Y m (Z m off the wall plane,
/// sliding at V m/s)" for `outputs` at clock time t_ns [ns] (the end of the step that found the
/// fall): position and speed along the wall of `outputs`.
std::string fellReason(const DriveOutputs& outputs, std::int64_t t_ns);

}  // namespace climbsim::drive
