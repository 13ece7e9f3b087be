#pragma once
/// @file
/// The two pictures of the original system (8-bit BGR, one pixel per depth pixel):
///  - edges: the depth image in grey (far_m black .. near_m white) with the outline of the
///    sealing strips in red and the borders between neighbouring segments in yellow;
///  - gaps: every sealing pixel grey by its gap h_s - h_g, black = tight (0) to white = open
///    (>= full_scale_gap_m); the other pixels show the depth image dimmed in blue.

#include <vector>

#include <opencv2/core.hpp>

#include "climbsim/shard_tiles/depth_grid.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// Depth in grey with the strips' edges drawn over it. `far_m` < `near_m` [m] set the grey scale.
cv::Mat edgesPicture(const DepthGrid& depth, const StripMasks& masks, double far_m, double near_m);

/// Gaps of the travel-limited sealing heights `sealing_m` (per sealing index) [m], white at
/// `full_scale_gap_m` (> 0) [m] and above; the background is the depth (far_m .. near_m) in blue.
cv::Mat gapsPicture(const DepthGrid& depth, const StripMasks& masks, const std::vector<double>& sealing_m,
                    double full_scale_gap_m, double far_m, double near_m);

}  // namespace climbsim::sealing
