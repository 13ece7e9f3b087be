#pragma once
/// @file
/// The robot's sealing strips rasterised into a depth camera's pixel grid
/// (docs/design.md#sealing-and-leakage): which pixel belongs to which sealing segment, and the
/// 8-neighbourhood between sealing pixels that the adaptation uses.
///
/// Membership: a pixel belongs to a strip when its centre lies within strip_width_m / 2 of
/// the segment's centre line (distance to the polyline of RobotGeometry::centreline_Robot,
/// so a strip has round caps at its ends). The strip is therefore the same set of wall
/// points at every resolution; only its sampling changes.
///
/// Junctions: where strips meet (outer arc to outer arc, radial wall to both arcs) a pixel
/// can be within half a width of several centre lines. It goes to the segment whose centre
/// line is nearest to the pixel centre; an exact tie goes to the lower segment index (the
/// geometry's order: outer1..N, radial1_2..N_1, inner1..N). Every sealing pixel thus
/// belongs to exactly one segment, and the rule depends on nothing but the geometry and the
/// grid.

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"

namespace climbsim::sealing {

/// The sealing pixels of one robot on one pixel grid. Built once per (robot, camera).
class StripMasks {
 public:
  /// Rasterises every segment of `geometry`. Throws ConfigError naming `source` (the robot
  /// file) when a strip reaches outside the grid (the sealing does not fit the camera's
  /// view) or a segment covers no pixel centre (the strip is narrower than the pixels).
  StripMasks(const RobotGeometry& geometry, const PixelGrid& grid, const std::string& source);

  const PixelGrid& grid() const { return grid_; }
  std::size_t segmentCount() const { return segment_pixels_.size(); }

  /// Segment index of pixel `raster` (row * W + col), or -1 outside every strip.
  int segmentOfPixel(std::size_t raster) const { return segment_of_pixel_[raster]; }

  /// Raster indices of all sealing pixels, ascending. Position k in this list is the
  /// "sealing index" k used by the adaptation's arrays.
  const std::vector<std::uint32_t>& sealingPixels() const { return sealing_pixels_; }
  /// Sealing index of raster pixel `raster`, or -1 outside every strip.
  std::int32_t sealingIndexOfPixel(std::size_t raster) const { return sealing_index_of_pixel_[raster]; }
  /// Sealing indices of segment `segment`'s pixels, ascending (= raster order).
  const std::vector<std::uint32_t>& segmentPixels(std::size_t segment) const { return segment_pixels_[segment]; }

 private:
  PixelGrid grid_;
  std::vector<std::int16_t> segment_of_pixel_;
  std::vector<std::int32_t> sealing_index_of_pixel_;
  std::vector<std::uint32_t> sealing_pixels_;
  std::vector<std::vector<std::uint32_t>> segment_pixels_;
};

}  // namespace climbsim::sealing
