#pragma once
/// @file
/// The depth image under the robot as the sealing model sees it (same convention as
/// idl/scene.idl DepthImage, without DDS): heights of the wall surface above the sealing
/// plane, in the robot frame R.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace climbsim::sealing {

/// Size and scale of a depth camera's pixel grid. The image centre is the robot centre;
/// row 0 is at the camera's +y edge and column 0 at its -x edge, so pixel (r, c) has its
/// centre at x = (c + 0.5 - W/2) s, y = (H/2 - r - 0.5) s in R (s = pixel_size_m).
struct PixelGrid {
  int width_px = 0;           ///< W, >= 1
  int height_px = 0;          ///< H, >= 1
  double pixel_size_m = 0.0;  ///< s, edge of a square pixel on the wall [m], > 0

  std::size_t pixelCount() const { return static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px); }
  /// x of the centres of column c in R [m].
  double xOfColumn_m(double c) const { return (c + 0.5 - width_px / 2.0) * pixel_size_m; }
  /// y of the centres of row r in R [m].
  double yOfRow_m(double r) const { return (height_px / 2.0 - r - 0.5) * pixel_size_m; }
  /// Fractional column whose centre lies at x [m] (inverse of xOfColumn_m).
  double columnOfX(double x_m) const { return x_m / pixel_size_m + width_px / 2.0 - 0.5; }
  /// Fractional row whose centre lies at y [m] (inverse of yOfRow_m).
  double rowOfY(double y_m) const { return height_px / 2.0 - 0.5 - y_m / pixel_size_m; }
  bool operator==(const PixelGrid& o) const {
    return width_px == o.width_px && height_px == o.height_px && pixel_size_m == o.pixel_size_m;
  }
};

/// The depth image's side [px] unless told otherwise; it covers the robot's view
/// (climbsim/robot/depth_view.hpp, robotDepthViewM) of wall.
inline constexpr int kDefaultCameraPx = 256;

/// A rectangle of pixels: rows row0 .. row0 + rows - 1, columns col0 .. col0 + cols - 1.
struct PixelBox {
  int row0 = 0;
  int col0 = 0;
  int rows = 0;
  int cols = 0;
  /// Whether `inner` lies inside this box.
  bool contains(const PixelBox& inner) const {
    return inner.row0 >= row0 && inner.col0 >= col0 && inner.row0 + inner.rows <= row0 + rows &&
           inner.col0 + inner.cols <= col0 + cols;
  }
  bool operator==(const PixelBox& o) const { return row0 == o.row0 && col0 == o.col0 && rows == o.rows && cols == o.cols; }
  /// "rows R+H cols C+W".
  std::string text() const {
    return "rows " + std::to_string(row0) + "+" + std::to_string(rows) + " cols " + std::to_string(col0) + "+" +
           std::to_string(cols);
  }
};

/// Support heights h_sup of edge pixels (sub-pixel leakage, docs/design.md#sub-pixel-leakage):
/// raster indices (row * W + col), ascending, and per index the highest the strip can be held
/// at that pixel's centre by the wall inside its square [m], finite. The adaptation starts such
/// a pixel at max(h_g, h_sup); its gap stays h_s - h_g.
struct SupportHeights {
  std::vector<std::uint32_t> raster;
  std::vector<float> height_m;
  bool empty() const { return raster.empty(); }
};

/// A depth image: h_g of docs/design.md#sealing-and-leakage per pixel.
struct DepthGrid {
  PixelGrid grid;
  /// Height of the wall above the sealing plane along R's z [m], row-major, W * H values;
  /// negative below the plane (crack, hole). Finite.
  std::vector<float> height_m;
  /// An upper bound of every height in the image [m] (the image's highest pixel, or the
  /// camera's near plane); +inf when unknown. Lets a shard bound the pixels it needs
  /// (shard_region.hpp): a value below some pixel gives wrong sealing heights.
  double upper_bound_m = std::numeric_limits<double>::infinity();
  /// Support heights of edge pixels (sub-pixel leakage); empty: none. upper_bound_m bounds
  /// them too.
  SupportHeights supports;
};

/// "" if `depth` is usable with `expected` (same size and pixel size, W * H finite values),
/// else one line naming the first problem (size, pixel size, pixel (row, col) and value).
std::string checkDepthGrid(const DepthGrid& depth, const PixelGrid& expected);

/// "" if `got` has `expected`'s size and pixel size (relative 1e-9), else one line naming it.
std::string checkPixelGrid(const PixelGrid& got, const PixelGrid& expected);

/// As checkDepthGrid without looking at the values: size, pixel size, value count, and the
/// support heights' count, order and range of indices (and that each is finite).
std::string checkDepthGridShape(const DepthGrid& depth, const PixelGrid& expected);

/// "pixel (row r, col c) height_m = V (must be finite)" for raster pixel `raster` of `grid`.
std::string nonFinitePixel(const PixelGrid& grid, std::size_t raster, float value);

}  // namespace climbsim::sealing
