#pragma once
/// @file
/// The sums of the leakage formula (leakage.hpp) over one frame's sealing, in two passes: the
/// gap of every adapted pixel along consecutive memory, then each segment's share-weighted sum
/// of its pixels' gaps in raster order, two segments at a time.
///
/// A segment's sum is one chain of dependent additions (its order is part of the result); two
/// segments' chains are independent, so running them side by side keeps the CPU busy while
/// each addition waits for the one before. Every value is the double the one-segment loop
/// gives: the same products added in the same order.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "climbsim/shard_tiles/pixel_runs.hpp"

namespace climbsim::sealing {

/// What the gap pass found over the pixels it visited.
struct GapScan {
  bool any_over_travel = false;  ///< some h_s > travel_m (NaN: no)
  bool any_without_wall = false;  ///< some h_g <= none_at_m
};

/// gap_m[k] = sealing_m[k] - ground_m[k] [m] for the sealing indices k of `runs`, and whether
/// any of them has sealing_m[k] > travel_m or ground_m[k] <= none_at_m.
GapScan scanGaps(const PixelRuns& runs, const double* sealing_m, const double* ground_m, double travel_m,
                 double none_at_m, double* gap_m);

/// One segment's running sums: sum of a_ij * gap_j [m] and the largest gap [m] (from 0).
struct GapSum {
  double sum_m = 0.0;
  double max_gap_m = 0.0;
};

/// One segment's leak pixels (sealing indices, ascending) and their shares a_ij.
struct LeakPixels {
  const std::vector<std::uint32_t>* pixels = nullptr;
  const std::vector<double>* shares = nullptr;
};

/// The sums of segments `a` and `b` over their pixels in order: sum_m += a_ij * gap_m[j],
/// max_gap_m = max(max_gap_m, gap_m[j]), the two chains interleaved.
void sumGapsPair(const LeakPixels& a, const LeakPixels& b, const double* gap_m, GapSum& sum_a, GapSum& sum_b);

/// The same for one segment.
void sumGaps(const LeakPixels& a, const double* gap_m, GapSum& sum);

}  // namespace climbsim::sealing
