#include "pacing.hpp"

#include <cmath>

namespace climbsim::clock {

WallClock::time_point pacedStart(const PacingAnchor& anchor, std::uint64_t step, std::int64_t dt_ns,
                                 double realtime_factor) {
  if (realtime_factor <= 0.0 || step <= anchor.step) {
    return anchor.wall;
  }
  const long double sim_ns = static_cast<long double>(step - anchor.step) * static_cast<long double>(dt_ns);
  const auto wall_ns = static_cast<std::int64_t>(std::llround(sim_ns / realtime_factor));
  return anchor.wall + std::chrono::duration_cast<WallClock::duration>(std::chrono::nanoseconds(wall_ns));
}

}  // namespace climbsim::clock
