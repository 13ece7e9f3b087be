#include "climbsim/shard_tiles/depth_grid.hpp"

#include <cmath>
#include <sstream>

namespace climbsim::sealing {

std::string nonFinitePixel(const PixelGrid& grid, std::size_t raster, float value) {
  std::ostringstream why;
  why << "pixel (row " << raster / grid.width_px << ", col " << raster % grid.width_px << ") height_m = " << value
      << " (must be finite)";
  return why.str();
}

std::string checkDepthGrid(const DepthGrid& depth, const PixelGrid& expected) {
  const std::string shape = checkDepthGridShape(depth, expected);
  if (!shape.empty()) return shape;
  for (std::size_t i = 0; i < depth.height_m.size(); ++i) {
    if (!std::isfinite(depth.height_m[i])) return nonFinitePixel(expected, i, depth.height_m[i]);
  }
  return {};
}

std::string checkPixelGrid(const PixelGrid& got, const PixelGrid& expected) {
  // Streams only for a problem: one costs more than the checks of a valid grid.
  if (got.width_px != expected.width_px || got.height_px != expected.height_px) {
    std::ostringstream why;
    why << "size " << got.width_px << "x" << got.height_px << " px, expected " << expected.width_px << "x"
        << expected.height_px;
    return why.str();
  }
  // A relative tolerance: the producer may compute the pixel size as view / pixels itself.
  if (!(std::abs(got.pixel_size_m - expected.pixel_size_m) <= 1e-9 * expected.pixel_size_m)) {
    std::ostringstream why;
    why.precision(17);
    why << "pixel_size_m = " << got.pixel_size_m << ", expected " << expected.pixel_size_m;
    return why.str();
  }
  return {};
}

std::string checkDepthGridShape(const DepthGrid& depth, const PixelGrid& expected) {
  const std::string grid = checkPixelGrid(depth.grid, expected);
  if (!grid.empty()) return grid;
  // Streams only for a problem (as checkPixelGrid).
  if (depth.height_m.size() != expected.pixelCount()) {
    std::ostringstream why;
    why << depth.height_m.size() << " heights for " << expected.width_px << "x" << expected.height_px << " px";
    return why.str();
  }
  if (depth.supports.raster.size() != depth.supports.height_m.size()) {
    std::ostringstream why;
    why << depth.supports.raster.size() << " support pixels with " << depth.supports.height_m.size() << " support heights";
    return why.str();
  }
  for (std::size_t i = 0; i < depth.supports.raster.size(); ++i) {
    if (depth.supports.raster[i] >= expected.pixelCount() || (i > 0 && depth.supports.raster[i] <= depth.supports.raster[i - 1])) {
      std::ostringstream why;
      why << "support_px[" << i << "] = " << depth.supports.raster[i] << " (must ascend below " << expected.pixelCount()
          << ")";
      return why.str();
    }
    if (!std::isfinite(depth.supports.height_m[i])) {
      std::ostringstream why;
      why << "support_m[" << i << "] = " << depth.supports.height_m[i] << " (must be finite)";
      return why.str();
    }
  }
  return {};
}

}  // namespace climbsim::sealing
