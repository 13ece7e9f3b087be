#pragma once
/// @file
/// The pixels a shard must adapt to get its own segments' sealing heights exactly (sharded
/// sealing).
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
/// h_max: with an upper bound U of every height in the image (DepthGrid::upper_bound_m: the
/// image's highest pixel, or the camera's near plane), a pixel with dist(q) >= D = (U + travel)
/// / k + margin cannot matter whatever its height, so h_max is the highest ground on the
/// pixels with dist < D ("the static region"; with U = near it bounds what a shard can ever
/// need of the image); without a bound the static region is the whole connected sealing.
///
/// With a finite bound U the region uses h_max = U and T = (U + travel) / k + margin (no pass
/// over the image: a frame costs only its adaptation); without one, h_max and h_min_own are
/// read from the pixels.
///
/// The own pixels' floors give a smaller T wherever the cut runs over ground that is not low.
/// Let depth(p) be the path distance of own pixel p from the nearest sealing pixel of another
/// shard, and L(p) = max(h_g(p), -travel) the value p has without any walk. A walk that leaves
/// the region reaches a pixel r with dist(r) >= T, then enters the own pixels at some o next to
/// a pixel o' of another shard; depth(p) <= d(o', p) <= d(o, p) + s sqrt 2 (s the pixel size),
/// so the walk is at least T + depth(p) - s sqrt 2 long and worth at most
/// h_max - k (T + depth(p) - s sqrt 2). It cannot beat L(p) when
///     T >= (h_max - L(p)) / k - depth(p) + s sqrt 2 + margin   for every own p,
/// which needs only the own pixels within (h_max + travel) / k of the cut (a frame reads them,
/// nearest first, and stops where no deeper pixel can ask for more). The region takes the
/// smaller of this T and the one above: on a flat wall 4 mm below U, 13 mm of halo instead of
/// 30 mm; where a crack crosses the cut, the same as before.
///
/// Pixels are kept in bands of dist kBandPixels pixel sizes wide: each region is the first B
/// bands, a little more than the bound asks for, adapted as runs along image rows in raster
/// order (pixel_runs.hpp; built on first use for each B) so that a frame reads the image and
/// its arrays forwards and touches only its region's memory. The list of the region's pixels
/// (sealingIndices) is ordered nearest band first, raster order within a band. Sealing pixels
/// not connected to an own pixel never matter and are left out.

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "climbsim/shard_tiles/pixel_runs.hpp"
#include "climbsim/shard_tiles/sealing_graph.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

class ShardRegion {
 public:
  /// Width of a band of dist, in pixel sizes.
  static constexpr int kBandPixels = 8;

  /// The region of `own_segments` (geometry indices) of `masks`; `masks` must outlive it.
  ShardRegion(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<std::size_t>& own_segments,
              double pixel_size_m);

  /// Number of leading local pixels to adapt for this frame (>= ownCount()): the whole bands
  /// that hold every pixel with dist < T (the smaller of the header's two bounds), for the
  /// ground h_g per raster pixel and the height bound U = upper_bound_m (+inf if unknown).
  /// std::invalid_argument naming the pixel if one it looks at is not finite.
  std::size_t activeCount(const SealingParams& params, const std::vector<float>& ground_m, double upper_bound_m) const;

  /// Number of leading local pixels (whole bands) that hold every pixel with dist < D =
  /// (U + travel) / k + margin for the height bound U = upper_bound_m ("the static region";
  /// with the camera's near plane: every pixel the shard can ever need).
  std::size_t staticCount(const SealingParams& params, double upper_bound_m) const;

  /// Number of leading local pixels (whole bands) that hold every pixel with dist < reach_m [m].
  std::size_t countWithin(double reach_m) const;

  /// As activeCount, in whole bands (>= 1): the region of the frame is runs(activeBands(...)).
  std::size_t activeBands(const SealingParams& params, const std::vector<float>& ground_m, double upper_bound_m) const;
  /// Number of bands that hold every pixel with dist < reach_m [m] (0 for reach <= 0).
  std::size_t bandsWithin(double reach_m) const;
  /// Number of bands of the region (all its pixels).
  std::size_t bandCount() const { return band_end_.size(); }
  /// Number of leading local pixels of the first `bands` bands.
  std::size_t countOfBands(std::size_t bands) const {
    return bands == 0 ? 0 : band_end_[std::min(bands, band_end_.size()) - 1];
  }
  /// The pixels of the first `bands` bands as runs (built on first use; not reentrant).
  const PixelRuns& runs(std::size_t bands) const;
  /// Band of every sealing pixel (sealing index), kNoBand if it is not connected to the own
  /// segments.
  const std::vector<std::uint16_t>& bandOfPixel() const { return band_of_pixel_; }
  static constexpr std::uint16_t kNoBand = 0xFFFF;

  /// Sealing index of every local pixel (bands of dist, raster order within a band).
  const std::vector<std::uint32_t>& sealingIndices() const { return order_; }
  /// dist per local pixel [m].
  const std::vector<double>& distance_m() const { return dist_m_; }
  /// Number of pixels of the own segments (dist 0, all in the first band).
  std::size_t ownCount() const { return own_raster_.size(); }
  /// Number of local pixels of the first band (own pixels and their nearest neighbours).
  std::size_t firstBandCount() const { return band_end_.empty() ? 0 : band_end_.front(); }
  /// Margin added to each reach [m].
  double margin_m() const { return margin_m_; }

 private:
  /// An own pixel that a pixel of another shard reaches along the strips.
  struct OwnPixel {
    std::uint32_t raster = 0;  ///< raster pixel (row * W + col)
    double depth_m = 0.0;      ///< path distance from the nearest pixel of another shard [m]
  };
  struct Layout;
  static Layout layoutOf(const StripMasks& masks, const std::vector<std::size_t>& own_segments, double pixel_size_m);
  ShardRegion(const StripMasks& masks, Layout layout);

  const StripMasks& masks_;
  std::vector<std::uint32_t> order_;  ///< sealing index per local index
  std::vector<std::uint16_t> band_of_pixel_;
  mutable std::vector<std::unique_ptr<PixelRuns>> runs_;  ///< per band count - 1
  std::vector<double> dist_m_;
  std::vector<std::uint32_t> raster_;  ///< raster pixel per local index
  std::vector<std::uint32_t> own_raster_;  ///< raster pixels of the own segments
  std::vector<std::size_t> band_end_;  ///< local index one past band b
  std::vector<OwnPixel> own_by_depth_;  ///< in bands of depth, raster order within a band
  double band_m_ = 0.0;
  double diagonal_m_ = 0.0;  ///< s sqrt 2 [m]
  double margin_m_ = 0.0;
};

}  // namespace climbsim::sealing
