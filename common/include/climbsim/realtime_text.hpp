#pragma once
/// @file
/// The real-time factor as people read it in a log line: "3.4x real time", with the digits a
/// small factor needs ("0.017x", not "0.0x"), and "n/a" where the wall time is too short to
/// measure (a run of a few steps).

#include <string>

namespace climbsim {

/// Shortest wall time [s] a real-time factor is given for: below it the steady clock's
/// resolution and the cost of starting and stopping are the whole measurement.
inline constexpr double kMinMeasuredWall_s = 1e-3;

/// "<f>x real time" for f = sim_s / wall_s [s/s]: f >= 10 without decimals, 1 <= f < 10 with
/// one, f < 1 with two significant digits ("0.017x"); "n/a real time (N ms wall)" when wall_s
/// is below kMinMeasuredWall_s or sim_s is not > 0 (nothing was simulated).
std::string realtimeText(double sim_s, double wall_s);

/// The same for a factor measured elsewhere (e.g. summary.json's realtime_factor); a factor
/// that is not finite and > 0 (no wall time was measured) is "n/a real time".
std::string realtimeText(double factor);

}  // namespace climbsim
