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
#include <vector>

#include "depth_camera.hpp"

namespace climbsim::scene {

/// Second difference of centre heights above which a pixel is sampled over its square [m].
constexpr double kEdgeThreshold_m = 2e-3;

/// The edge pixels (raster indices, ascending) among rows row0 .. row0 + rows - 1 and columns
/// col0 .. col0 + cols - 1 of a W x H image of centre heights `centre_m` (row-major, at least
/// far; the neighbours of those pixels filled), and among `mask`'s pixels when it is given.
/// `reference`: every pixel decided one by one with the border's expressions (the reference
/// path, RenderOptions::reference_raster); the same pixels either way.
std::vector<std::uint32_t> edgePixels(const std::vector<float>& centre_m, int width_px, int height_px, int row0,
                                      int col0, int rows, int cols, const PixelMask* mask, double threshold_m,
                                      bool reference = false);

/// `mask` grown by one pixel in each of the 8 directions (within the image).
std::shared_ptr<const PixelMask> dilatedMask(const PixelMask& mask);

/// The smallest tile (rows, columns) that holds every pixel of `raster_pixels` (not empty), with
/// a mask of exactly them.
PixelTile tileOf(int width_px, int height_px, const std::vector<std::uint32_t>& raster_pixels);

}  // namespace climbsim::scene
