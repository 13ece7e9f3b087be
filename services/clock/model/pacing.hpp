#pragma once
/// @file
/// Real-time factor pacing: when may a step start on the wall clock.

#include <chrono>
#include <cstdint>

namespace climbsim::clock {

using WallClock = std::chrono::steady_clock;

/// A pacing anchor: step `step` was (or may be) released at wall time `wall`.
/// Re-anchored at every resume and change of real-time factor so that a pause does
/// not make the clock race to catch up.
struct PacingAnchor {
  WallClock::time_point wall;
  std::uint64_t step = 0;
};

/// Earliest wall time at which step `step` may start:
///   wall = anchor.wall + (step - anchor.step) * dt_ns / realtime_factor,
/// or anchor.wall if realtime_factor == 0 (as fast as possible). step >= anchor.step;
/// realtime_factor >= 0; dt_ns > 0. Exact to the nanosecond for up to 2^53 ns of offset.
WallClock::time_point pacedStart(const PacingAnchor& anchor, std::uint64_t step, std::int64_t dt_ns,
                                 double realtime_factor);

}  // namespace climbsim::clock
