#pragma once
/// @file
/// Which sealing segments shard I of N computes (sharded sealing).
///
/// The adaptation couples neighbouring pixels, so a shard must adapt a halo around its own
/// segments (shard_region.hpp). A halo is cheapest when a shard's segments lie together: the
/// segments are ordered by the angle of their pixels' centroid about the robot centre
/// (atan2(y, x) in R, from -pi) and cut into N contiguous runs of about equal pixel counts:
/// segment s (in that order, with P_before pixels before it and P_s of its own, P in all) goes to
/// shard floor(N (P_before + P_s / 2) / P). Outer arc, radial wall and inner arc of one sector
/// therefore go to the same shard. The rule depends on nothing but the masks.

#include <cstddef>
#include <string>
#include <vector>

#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The segments (geometry indices, ascending) of every shard 0..count-1. Throws ConfigError
/// naming `--shard` when count is 0, exceeds the number of segments, or leaves a shard
/// without a segment.
std::vector<std::vector<std::size_t>> partitionSegments(const StripMasks& masks, std::size_t count);

/// This process's share of the segments: "--shard I/N".
struct ShardSpec {
  std::size_t index = 0;  ///< I, < count
  std::size_t count = 1;  ///< N, >= 1

  /// Parses "I/N"; ConfigError naming --shard and the value if malformed or I >= N.
  static ShardSpec parse(const std::string& text);
  /// This shard's segment indices (partitionSegments), ascending. ConfigError naming --shard
  /// if a shard would get none (N larger than the segment count).
  std::vector<std::size_t> segments(const StripMasks& masks) const;
};

}  // namespace climbsim::sealing
