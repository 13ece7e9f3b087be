#pragma once
/// @file
/// An optional bound on a segment's leakage by the channel the air must pass through
/// (SealingParams::channel_bound, off by default).
///
/// docs/design.md#sealing-and-leakage sums the gap under every pixel of a strip:
/// L_i = l_i (L_basic + kappa_L * mean gap), i.e. kappa_L times the gap area seen from above
/// divided by the strip width. Where a crack crosses a strip that is its channel cross-section (width x unclosed depth).
/// Where a crack runs *along* a strip, under it, the sum counts the crack's whole length, as if
/// air crossed the strip everywhere; but with the strip's edges touching the wall on both
/// sides, air enters and leaves the strip region only where the gap reaches its edge lines.
/// The bound: the gap area across a segment cannot exceed the open cross-section along either
/// of its two edge lines,
///     A_side = l_i * (mean gap over the segment's edge pixels on that side),
///     L_i <= l_i L_basic + kappa_L * min(A_side_a, A_side_b)
/// (the mean times l_i rather than a sum times the pixel size: a staircase of pixels along a
/// slanted edge has no exact length; so a uniform gap gives exactly the unbounded value).
/// An edge pixel is a strip pixel with a 4-neighbour outside every strip; its side is the side
/// of the segment's centre line on which that neighbour's centre lies.

#include <array>
#include <cstdint>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The edge pixels of every segment, by side. Built once per (robot, camera).
class StripEdges {
 public:
  StripEdges(const RobotGeometry& geometry, const StripMasks& masks);

  /// Sealing indices of segment `segment`'s edge pixels on side 0 (left of the centre line, in
  /// its direction) or 1 (right), ascending.
  const std::vector<std::uint32_t>& edgePixels(std::size_t segment, int side) const {
    return edges_[segment][static_cast<std::size_t>(side)];
  }

  /// min(A_side_0, A_side_1) of segment `segment` of length l_i = length_m [m^2] from the
  /// ground per raster pixel and the travel-limited sealing heights per sealing index.
  double channelArea_m2(const StripMasks& masks, std::size_t segment, double length_m,
                        const std::vector<float>& ground_m, const std::vector<double>& sealing_m) const;

 private:
  std::vector<std::array<std::vector<std::uint32_t>, 2>> edges_;
};

}  // namespace climbsim::sealing
