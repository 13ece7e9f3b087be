#pragma once
/// @file
/// The pixels a shard must adapt to get its own segments' sealing heights exactly (issue 14).
///
/// Whole-sealing fixpoint (adaptation.hpp): h_s(p) = max(h_g(p), max_q (h_g(q) - k d(p, q)))
/// with k = max_slope and d the shortest 8-connected path through sealing pixels; after the
/// travel limit only max(h_s(p), -travel) matters. Let dist(r) be the path distance [m] of
/// pixel r from the nearest pixel of the shard's own segments. A walk from q to an own pixel
/// p that passes a pixel r with dist(r) >= T has the value
///     <= h_max - k T,
/// h_max the highest ground on the pixels q it can start from. So with
///     T = min(h_max + travel, h_max - h_min_own) / k + margin
/// (h_min_own the lowest ground on own pixels) such a walk can never beat
/// max(h_g(p), -travel), and the fixpoint of the pixels with dist < T alone gives every own
/// pixel the whole sealing's value, the same doubles (SubgraphAdapter: its walks are the
/// region's walks, evaluated in the same float operations). The margin (two diagonal pixel
/// steps) covers the rounding of the float walk values and of the distances.
///
/// h_max: a pixel with dist(q) >= D = (near + travel) / k + margin cannot matter whatever its
/// height (the camera clamps heights to <= near), so h_max is the highest ground on the pixels
/// with dist < D ("the static region", which also bounds what a shard needs of the image);
/// without a known near the static region is the whole connected sealing.
///
/// Pixels are kept in the order of dist (ties by sealing index), so each region is a prefix.
/// Sealing pixels not connected to an own pixel never matter and are left out.

#include <cstddef>
#include <limits>
#include <vector>

#include "adaptation.hpp"
#include "sealing_params.hpp"
#include "strip_masks.hpp"

namespace climbsim::sealing {

class ShardRegion {
 public:
  /// The region of `own_segments` (geometry indices) of `masks`; `masks` must outlive it.
  ShardRegion(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<std::size_t>& own_segments,
              double pixel_size_m);

  /// Number of leading local pixels to adapt for this frame (>= ownCount()): the prefix with
  /// dist < T of the header's bound, for the ground h_g per raster pixel and the camera's
  /// highest height near_m (+inf if unknown).
  std::size_t activeCount(const SealingParams& params, const std::vector<float>& ground_m, double near_m) const;

  /// Number of leading local pixels with dist < D = (near + travel) / k + margin: every
  /// pixel the shard can ever need ("the static region").
  std::size_t staticCount(const SealingParams& params, double near_m) const;

  /// Pixels with dist < reach_m [m].
  std::size_t countWithin(double reach_m) const;

  const SubgraphAdapter& adapter() const { return adapter_; }
  /// Sealing index of every local pixel, in the order of dist.
  const std::vector<std::uint32_t>& sealingIndices() const { return adapter_.graph().sealing_index; }
  /// dist per local pixel [m], ascending.
  const std::vector<double>& distance_m() const { return dist_m_; }
  /// Pixels of the own segments (dist 0): the first ownCount() local pixels.
  std::size_t ownCount() const { return own_count_; }
  /// Margin added to each reach [m].
  double margin_m() const { return margin_m_; }

 private:
  struct Layout;
  static Layout layoutOf(const StripMasks& masks, const std::vector<std::size_t>& own_segments, double pixel_size_m);
  ShardRegion(const StripMasks& masks, const Neighbourhood& nbh, Layout layout);

  const StripMasks& masks_;
  std::vector<double> dist_m_;
  std::vector<std::uint32_t> raster_;  ///< raster pixel per local index
  std::size_t own_count_ = 0;
  double margin_m_ = 0.0;
  SubgraphAdapter adapter_;
};

}  // namespace climbsim::sealing
