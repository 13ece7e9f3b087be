#pragma once
/// @file
/// The sweep's one progress line: variants done (fell, slid, failed), running, queued, the time
/// since the start and an estimate of the time left.

#include <cstddef>
#include <string>

namespace climbsim::sweep {

/// The counts of a sweep under way.
struct SweepCounts {
  std::size_t total = 0;
  std::size_t done = 0;     ///< ended with a result (in sweep.csv) or failed
  std::size_t fell = 0;     ///< of done: the robot fell
  std::size_t slid = 0;     ///< of done: stayed on the wall but slid beyond the slide limit
  std::size_t failed = 0;   ///< of done: failed (own failure or lost beyond retries)
  std::size_t running = 0;
  std::size_t queued = 0;
};

/// "sweep: [#####.........] 3/8 done (1 fell, 1 slid, 0 failed), 2 running, 3 queued, 12 s,
/// about 20 s left". The time left is elapsed_s / done * (total - done): the variants done so
/// far are the measure of those to come (none before the first is done).
std::string progressLine(const SweepCounts& c, double elapsed_s);

}  // namespace climbsim::sweep
