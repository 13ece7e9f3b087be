#pragma once
/// @file
/// A set of sealing pixels as runs along image rows, and the 8-neighbourhood of the whole
/// sealing without a table of neighbour indices (less memory per pixel and frame).
///
/// Sealing indices follow raster order (StripMasks::sealingPixels), so the sealing pixels of
/// one row that touch each other have consecutive sealing indices, and so have the up to three
/// neighbours of a pixel in the row above or below. Arrays per sealing index are therefore
/// read along runs of consecutive memory: a shard that adapts only its region touches only
/// the memory of its region's runs.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// Sealing pixels as runs: each run is a stretch of one image row, consecutive columns and
/// consecutive sealing indices.
struct PixelRuns {
  struct Run {
    std::uint32_t first = 0;   ///< sealing index of its first (leftmost) pixel
    std::uint32_t count = 0;   ///< pixels
    std::uint32_t raster = 0;  ///< raster pixel (row * W + col) of its first pixel
  };
  /// The pixel pairs between a run and a run of the next row that are neighbours with the
  /// same column offset: upper + t in row r and lower + t in row r + 1, t = 0 .. count - 1.
  struct VerticalPairs {
    std::uint32_t upper = 0;     ///< sealing index in row r
    std::uint32_t lower = 0;     ///< sealing index in row r + 1
    std::uint32_t count = 0;     ///< pairs
    std::uint32_t diagonal = 0;  ///< 1: the lower pixel is one column left or right, else 0
  };
  std::vector<Run> runs;              ///< ascending sealing index
  std::vector<VerticalPairs> pairs;   ///< every neighbouring pair between rows, once
  std::size_t pixels = 0;             ///< sum of the runs' counts
};

/// The runs of the sealing pixels k of `masks` with member(k), and their vertical pairs.
PixelRuns pixelRunsOf(const StripMasks& masks, const std::function<bool(std::uint32_t)>& member);

/// The runs of the sealing pixels k with key(k) >= 0, a run also ending where the key changes;
/// `keys` receives each run's key. No vertical pairs.
PixelRuns pixelRunsByKey(const StripMasks& masks, const std::function<int(std::uint32_t)>& key, std::vector<int>& keys);

/// The 8 neighbours of every sealing pixel in 9 bytes instead of 8 indices: which of them are
/// sealing pixels, and the sealing index of the first existing one in the row above and below.
/// Bit j of `mask` stands for Neighbourhood::kOffsets[j] (sealing_graph.hpp): 0 right, 1 down,
/// 2 left, 3 up, 4 down-right, 5 down-left, 6 up-right, 7 up-left.
struct NeighbourLinks {
  std::vector<std::uint32_t> up_first;    ///< sealing index of the leftmost existing up neighbour
  std::vector<std::uint32_t> down_first;  ///< sealing index of the leftmost existing down neighbour
  std::vector<std::uint8_t> mask;         ///< bit j: neighbour j is a sealing pixel

  explicit NeighbourLinks(const StripMasks& masks);
  std::size_t size() const { return mask.size(); }
};

}  // namespace climbsim::sealing
