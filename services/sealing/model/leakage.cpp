#include "leakage.hpp"

#include <algorithm>

namespace climbsim::sealing {

void applyTravel(const SealingParams& params, std::vector<double>& sealing_m) {
  const double lowest_m = -params.travel_m;
  for (double& h : sealing_m) h = std::max(h, lowest_m);
}

SegmentLeak segmentLeak(const SealingParams& params, const StripMasks& masks, std::size_t segment,
                        const std::vector<float>& ground_m, const std::vector<double>& sealing_m) {
  const auto& pixels = masks.sealingPixels();
  const auto& mine = masks.leakPixels(segment);
  const auto& shares = masks.leakShares(segment);
  SegmentLeak leak;
  leak.pixels = mine.size();
  double sum_m = 0.0;
  for (std::size_t n = 0; n < mine.size(); ++n) {
    const std::uint32_t k = mine[n];
    const double gap_m = sealing_m[k] - static_cast<double>(ground_m[pixels[k]]);
    sum_m += shares[n] * gap_m;
    leak.max_gap_m = std::max(leak.max_gap_m, gap_m);
    if (sealing_m[k] > params.travel_m) ++leak.over_travel_px;
  }
  leak.mean_gap_m = sum_m / masks.shareSum(segment);
  leak.leak_area_m2 = params.segment_length_m[segment] * (params.basic_gap_m + params.kappa_L * leak.mean_gap_m);
  return leak;
}

SegmentLeak closedSegmentLeak(const SealingParams& params, const StripMasks& masks, std::size_t segment) {
  SegmentLeak leak;
  leak.pixels = masks.leakPixels(segment).size();
  leak.leak_area_m2 = params.segment_length_m[segment] * (params.basic_gap_m + params.kappa_L * 0.0);
  return leak;
}

}  // namespace climbsim::sealing
