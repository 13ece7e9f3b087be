#pragma once
/// @file
/// The sealing pixels as a graph (docs/design.md#sealing-and-leakage): the 8-neighbourhood of
/// the pixel grid restricted to sealing pixels (of any segment: the strips are one continuous
/// sealing, so the adaptation runs across junctions), and the largest height step between
/// neighbours, the slope times their centre distance:
///   step_orth_m = max_slope * s          (left, right, up, down)
///   step_diag_m = max_slope * s * sqrt 2 (diagonals)
/// so the physics does not change with the resolution s. The adaptation (the sealing model)
/// runs on it; a shard's region (shard_region.hpp) measures its path distances along it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The 8 neighbour offsets and their steps, shared by the oracle and the production path.
struct Neighbourhood {
  /// (d_row, d_col) of the 8 neighbours; entries 0..3 are orthogonal, 4..7 diagonal.
  static constexpr std::array<std::array<int, 2>, 8> kOffsets{
      {{{0, 1}}, {{1, 0}}, {{0, -1}}, {{-1, 0}}, {{1, 1}}, {{1, -1}}, {{-1, 1}}, {{-1, -1}}}};
  /// Largest height step to an orthogonal (k < 4) or diagonal neighbour [m].
  std::array<double, 8> step_m{};

  /// Steps for `max_slope` [m/m] (> 0) on pixels of `pixel_size_m` [m].
  Neighbourhood(double max_slope, double pixel_size_m);
};

/// The whole sealing's pixel graph in sealing-index order: `neighbours[8 k + j]` is the
/// sealing index of k's neighbour at Neighbourhood::kOffsets[j], or -1 (outside the strips).
/// Built once per region (shard_region.hpp measures distances along it); the adaptation
/// itself uses the runs and links of pixel_runs.hpp.
struct SealingSubgraph {
  std::vector<std::uint32_t> sealing_index;
  std::vector<std::int32_t> neighbours;
  std::size_t size() const { return sealing_index.size(); }
};

/// The whole sealing of `masks` in sealing-index order.
SealingSubgraph wholeSealingGraph(const StripMasks& masks);

}  // namespace climbsim::sealing
