#pragma once
/// @file
/// The robot's sealing strips rasterised into a depth camera's pixel grid
/// (docs/design.md#sealing-and-leakage): which pixel belongs to which sealing segment, and the
/// 8-neighbourhood between sealing pixels that the adaptation uses.
///
/// Two outlines (StripOutline), chosen by the scenario's depth_camera.subpixel
/// (docs/design.md#sub-pixel-leakage):
///
/// Pixel centres (kPixelCentres, the default): a pixel belongs to a strip when its centre lies
/// within strip_width_m / 2 of the segment's centre line (distance to the polyline of
/// RobotGeometry::centreline_Robot, so a strip has round caps at its ends). Where strips meet
/// (outer arc to outer arc, radial wall to both arcs) a pixel can be within half a width of
/// several centre lines: it goes to the segment whose centre line is nearest to the pixel
/// centre, an exact tie to the lower segment index (the geometry's order: outer1..N,
/// radial1_2..N_1, inner1..N). Every sealing pixel belongs to exactly one segment, with the
/// share a_ij = 1 of it.
///
/// Sub-pixel shares (kSubpixelShares): a pixel's square is sampled at kCoverageSubpixels x
/// kCoverageSubpixels points (the centres of equal sub-squares). A point belongs to the strip
/// of the segment whose centre line is nearest, if that line is within strip_width_m / 2, an
/// exact tie to the lower segment index. A pixel's share a_ij of segment i is the fraction of
/// its points in strip i (a multiple of 1 / 64), so the strips' outlines lie within the
/// pixels, not on their edges: sum_j a_ij s^2 is strip i's area (what its neighbours do not
/// take at junctions) to a fraction of a pixel along its outline, at every resolution. The
/// sealing pixels are every pixel with a share of some strip; each belongs to one segment
/// (segmentOfPixel): the one with the largest share, a tie to the lower index.
///
/// In both, the adaptation runs over all sealing pixels, the shard partition and the pictures
/// use segmentOfPixel, and a segment's leakage reads every pixel with a share of it
/// (leakPixels, leakShares): with sub-pixel shares a pixel at a junction or on an outline
/// counts for each strip by its share.

#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"

namespace climbsim::sealing {

/// Which pixels make up a strip and by how much (see the file's comment).
enum class StripOutline {
  kPixelCentres,    ///< a pixel whose centre lies in a strip, whole
  kSubpixelShares,  ///< every pixel whose square meets a strip, by the share it covers
};

/// The sealing pixels of one robot on one pixel grid. Built once per (robot, camera).
class StripMasks {
 public:
  /// Rasterises every segment of `geometry`. Throws ConfigError naming `source` (the robot
  /// file) when a strip reaches outside the grid (the sealing does not fit the camera's
  /// view) or no pixel belongs to a segment (the strips are narrower than the pixels).
  StripMasks(const RobotGeometry& geometry, const PixelGrid& grid, const std::string& source,
             StripOutline outline = StripOutline::kPixelCentres);

  const PixelGrid& grid() const { return grid_; }
  StripOutline outline() const { return outline_; }
  std::size_t segmentCount() const { return segment_pixels_.size(); }

  /// Segment index of pixel `raster` (row * W + col), or -1 outside every strip.
  int segmentOfPixel(std::size_t raster) const { return segment_of_pixel_[raster]; }

  /// Raster indices of all sealing pixels, ascending. Position k in this list is the
  /// "sealing index" k used by the adaptation's arrays.
  const std::vector<std::uint32_t>& sealingPixels() const { return sealing_pixels_; }
  /// Sealing index of raster pixel `raster`, or -1 outside every strip.
  std::int32_t sealingIndexOfPixel(std::size_t raster) const { return sealing_index_of_pixel_[raster]; }
  /// Sealing indices of the pixels that belong to segment `segment` (segmentOfPixel), ascending
  /// (= raster order).
  const std::vector<std::uint32_t>& segmentPixels(std::size_t segment) const { return segment_pixels_[segment]; }
  /// Sealing indices of every pixel with a share of segment `segment`'s strip, ascending: what
  /// its leakage reads (a superset of segmentPixels).
  const std::vector<std::uint32_t>& leakPixels(std::size_t segment) const { return leak_pixels_[segment]; }
  /// The share a_ij of each of leakPixels(segment), same order, in (0, 1] (1 with pixel centres).
  const std::vector<double>& leakShares(std::size_t segment) const { return leak_shares_[segment]; }
  /// sum_j a_ij: segment i's strip area in pixels (exact: the shares are multiples of 1 / 64).
  double shareSum(std::size_t segment) const { return share_sum_[segment]; }

  /// Sampling points per pixel along each axis (kSubpixelShares).
  static constexpr int kCoverageSubpixels = 8;

 private:
  /// Fill the members below for each outline (the constructor has checked the geometry).
  void outlineByCentres(const RobotGeometry& geometry);
  void outlineByShares(const RobotGeometry& geometry);

  PixelGrid grid_;
  StripOutline outline_;
  std::vector<std::int16_t> segment_of_pixel_;
  std::vector<std::int32_t> sealing_index_of_pixel_;
  std::vector<std::uint32_t> sealing_pixels_;
  std::vector<std::vector<std::uint32_t>> segment_pixels_;
  std::vector<std::vector<std::uint32_t>> leak_pixels_;
  std::vector<std::vector<double>> leak_shares_;
  std::vector<double> share_sum_;
};

}  // namespace climbsim::sealing
