#pragma once
/// @file
/// The pixels of a depth image each sealing shard reads (shard_region.hpp's static region):
/// what `climbsim-scene --tile I/N` renders and sends for shard I/N, and what the shard checks a
/// tile against. The scene and the sealing ask the same object, so they agree on every pixel.

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "climbsim/shard_tiles/depth_grid.hpp"
#include "climbsim/shard_tiles/sealing_graph.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "climbsim/shard_tiles/shard_region.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The regions of the subsets of segments asked for (built on first use), and the pixels they
/// need of an image whose heights are bounded. Not thread-safe: its owner serialises the calls.
class ShardPixels {
 public:
  /// For the strips `masks` (must outlive this object) and the sealing's max_slope and
  /// travel_m (`params`). std::invalid_argument for max_slope <= 0 (Neighbourhood).
  ShardPixels(const SealingParams& params, const StripMasks& masks);

  /// The region of `segments` (distinct geometry indices; must not be all of them).
  const ShardRegion& region(const std::vector<std::size_t>& segments) const;

  /// The pixels `segments` can read of an image whose heights are at most `upper_bound_m` [m]
  /// (the camera's near plane: of any image): the bounding box of the region's static part,
  /// of every sealing pixel for all segments. A tile of the image that contains this box is all
  /// a shard needs.
  PixelBox neededBox(const std::vector<std::size_t>& segments, double upper_bound_m) const;
  /// The pixels themselves whose box neededBox is, as raster indices (row * W + col), ascending:
  /// what a masked tile for the shard must hold.
  std::vector<std::uint32_t> neededPixels(const std::vector<std::size_t>& segments, double upper_bound_m) const;
  /// How many pixels neededPixels gives (whole bands of the region: bounds that give the same
  /// count give the same pixels), without listing them.
  std::size_t neededCount(const std::vector<std::size_t>& segments, double upper_bound_m) const;

 private:
  SealingParams params_;
  const StripMasks& masks_;
  Neighbourhood nbh_;
  mutable std::map<std::vector<std::size_t>, std::unique_ptr<ShardRegion>> regions_;
};

}  // namespace climbsim::sealing
