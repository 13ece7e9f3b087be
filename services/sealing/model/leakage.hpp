#pragma once
/// @file
/// The travel limit and the leakage per sealing segment (docs/design.md#sealing-and-leakage).
///
/// Travel: the strip's rest plane is the sealing plane z = 0 of R. It extends at most
/// travel_m towards the wall (below the plane), so the sealing height after the adaptation is
/// limited to h_s >= -travel_m; where the wall lies deeper (a crack or hole deeper than the
/// travel) a gap stays open. Above +travel_m (a bump the strip cannot retract from) the strip
/// is not limited: it stays in contact (gap 0, no leak) and the pixel is counted as
/// over-travel. Pressing the robot off the wall there is the drive's contact physics, not the
/// sealing's; the count is a diagnostic.
/// The limit commutes with the adaptation (the least slope-limited function above
/// max(h_g, -travel) is max(h_s, -travel)), so it is applied afterwards.
///
/// Gap of a sealing pixel j: h_s(j) - h_g(j) >= 0. Leakage area of segment i, with a_ij the
/// share of pixel j's square in strip i (StripMasks::leakShares; S_i the pixels with a share):
///   L_i = l_i * (L_basic + kappa_L * sum_{j in S_i} a_ij (h_s(j) - h_g(j)) / sum_{j in S_i} a_ij)
/// with the sums taken over S_i's pixels in raster order (deterministic, and independent of
/// which other segments are evaluated).

#include <cstddef>
#include <vector>

#include "climbsim/shard_tiles/sealing_params.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The result for one segment.
struct SegmentLeak {
  std::size_t pixels = 0;          ///< |S_i|: pixels with a share of the strip
  double mean_gap_m = 0.0;         ///< sum of a_ij gaps / sum of a_ij [m], >= 0
  double max_gap_m = 0.0;          ///< largest gap of a pixel [m]
  double leak_area_m2 = 0.0;       ///< L_i [m^2]
  std::size_t over_travel_px = 0;  ///< pixels whose sealing height exceeds +travel_m
  /// Share of the strip (sum of a_ij) whose depth is at the camera's far limit, 0..1: no wall within reach (the
  /// strip hangs past the scene's edge, or over a hole deeper than far), a fully open gap
  /// there. Filled by SealingModel::step, which is given the image's far limit.
  double no_surface_share = 0.0;
};

/// Applies the travel limit in place: h_s <- max(h_s, -travel_m) per sealing index.
void applyTravel(const SealingParams& params, std::vector<double>& sealing_m);

/// L_i, mean and max gap of segment `segment` from the ground h_g per raster pixel and the
/// travel-limited sealing heights per sealing index [m].
SegmentLeak segmentLeak(const SealingParams& params, const StripMasks& masks, std::size_t segment,
                        const std::vector<float>& ground_m, const std::vector<double>& sealing_m);

/// The leakage of a wall that the sealing closes completely: l_i * L_basic, no gap.
SegmentLeak closedSegmentLeak(const SealingParams& params, const StripMasks& masks, std::size_t segment);

}  // namespace climbsim::sealing
