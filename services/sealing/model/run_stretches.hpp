#pragma once
/// @file
/// Runs of sealing pixels (PixelRuns) as stretches of consecutive sealing indices: the runs of
/// one row follow each other in the arrays per sealing index, and the whole sealing is a single
/// stretch. A pass that needs only the sealing index goes along the stretches, in long loops.

#include <cstdint>

#include "climbsim/shard_tiles/pixel_runs.hpp"

namespace climbsim::sealing {

/// Calls fn(first, end) for each maximal stretch [first, end) of consecutive sealing indices
/// that `runs` cover, ascending.
template <class Fn>
void forEachStretch(const PixelRuns& runs, Fn&& fn) {
  for (std::size_t r = 0; r < runs.runs.size();) {
    const std::uint32_t first = runs.runs[r].first;
    std::uint32_t end = first + runs.runs[r].count;
    for (++r; r < runs.runs.size() && runs.runs[r].first == end; ++r) end += runs.runs[r].count;
    fn(first, end);
  }
}

}  // namespace climbsim::sealing
