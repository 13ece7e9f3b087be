#pragma once
/// @file
/// Where a depth pixel needs more than its centre ray (docs/design.md#sealing-and-leakage): the
/// pixels whose square an edge of the wall (a crack's wall, a step, a hole's rim) may cross.
///
/// A pixel p is an edge pixel when, with h the centre heights (at least far) and d one of the
/// four directions (along a row, a column, both diagonals), |h(p - d) - 2 h(p) + h(p + d)|
/// exceeds the threshold (a neighbour outside the image: |h(p + d) - h(p)| instead). A straight
/// edge that crosses p's square separates the centres of p's 3 x 3 neighbourhood, so a step
/// higher than the threshold makes p an edge pixel; a plane never does. The decision reads
/// only the centres of p's neighbourhood, so a tile that renders them decides as the whole
/// image does.

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "depth_camera.hpp"
#include "depth_rasterizer.hpp"

namespace climbsim::scene {

/// Second difference of centre heights above which a pixel is sampled over its square [m].
constexpr double kEdgeThreshold_m = 2e-3;

/// The edge pixels (raster indices, ascending) among rows row0 .. row0 + rows - 1 and columns
/// col0 .. col0 + cols - 1 of a W x H image of centre heights `centre_m` (row-major, at least
/// far; the neighbours of those pixels filled), and among `mask`'s pixels when it is given.
/// `reference`: every pixel decided one by one with the border's expressions (the reference
/// path, RenderOptions::reference_raster); else the inner pixels a row at a time by `kernel`'s
/// variant (depth_rasterizer.hpp: bendingPixelsKernel). The same pixels either way.
std::vector<std::uint32_t> edgePixels(const std::vector<float>& centre_m, int width_px, int height_px, int row0,
                                      int col0, int rows, int cols, const PixelMask* mask, double threshold_m,
                                      bool reference = false, RasterKernel kernel = RasterKernel::kAuto);

/// The direction across the wall's edge at pixel (row, col) of a W x H image of centre heights
/// `centre_m` (its 3 x 3 neighbourhood filled; a neighbour outside the image takes the nearest
/// pixel's value): the eigenvector of the larger eigenvalue (in magnitude) of the second
/// differences [[h_cc, h_cr], [h_cr, h_rr]] (along +column, along +row), not normalised, which a
/// step and a kink alike have across their line; (0, 0) where the neighbourhood does not bend.
std::pair<double, double> edgeNormal(const std::vector<float>& centre_m, int width_px, int height_px, int row, int col);

/// A support bound from an edge pixel p [m] (docs/design.md#sub-pixel-leakage): the highest the
/// sealing strip, falling by `slope` [m/m] per metre of the adaptation's 8-connected distance,
/// can be held at the point `at` [px] from p's centre (p's own centre or a neighbour's) by the
/// wall p's samples see,
///
///     max_i ( z_i - slope * s * d_i )
///
/// with z_i [m] the height of sample i at `offsets[i]` [px] from p's centre (subpixelOffsets),
/// s = `pixel_m` and d_i [px] the 8-connected distance from `at` to the line through sample i
/// along the edge: |(o_i - at) . n| / max(|n_x|, |n_y|, (|n_x| + |n_y|) / sqrt 2) for the unit
/// normal n of `normal` (edgeNormal); where that is (0, 0), to the sample itself,
/// max(|v_x|, |v_y|) + (sqrt 2 - 1) min(|v_x|, |v_y|) for v = o_i - at. A sample on the wall's
/// high side of a straight edge thus stands for the edge itself within the pattern's spacing
/// (1/16 px across an edge along the rows or the columns); on a plane of slope below `slope`
/// the bound lies below the plane's height at `at`.
double supportHeight_m(const std::vector<double>& z_m, const std::vector<std::pair<double, double>>& offsets,
                       std::pair<double, double> normal, double slope, double pixel_m,
                       std::pair<double, double> at = {0.0, 0.0});

/// supportHeight_m of one edge pixel at several points `at`: the normal's part once.
class SupportBound {
 public:
  SupportBound(std::pair<double, double> normal, double slope, double pixel_m);
  /// supportHeight_m of the `count` samples z_m[0 .. count - 1] at `offsets` (bit for bit).
  double at(const double* z_m, std::size_t count, const std::vector<std::pair<double, double>>& offsets,
            std::pair<double, double> at) const;

 private:
  double length_, nx_, ny_;  // |normal|, the unit normal ((0, 0) where normal is (0, 0))
  double octagon_;           // the unit octagon's extent along the unit normal
  double fall_m_per_px_;     // slope * pixel_m
};

/// `mask` grown by one pixel in each of the 8 directions (within the image).
std::shared_ptr<const PixelMask> dilatedMask(const PixelMask& mask);

/// The smallest tile (rows, columns) that holds every pixel of `raster_pixels` (not empty), with
/// a mask of exactly them.
PixelTile tileOf(int width_px, int height_px, const std::vector<std::uint32_t>& raster_pixels);

}  // namespace climbsim::scene
