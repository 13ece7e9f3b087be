#pragma once
/// @file
/// The orthographic depth camera under the robot (docs/design.md#models, idl/scene.idl DepthImage):
/// its parameters, its image and the 8-bit quantisation of the original system.
///
/// Camera frame C = robot frame R: origin at the robot centre in the sealing plane, z pointing
/// away from the wall; the camera looks along -z. Every pixel casts one ray parallel to -z
/// through its centre (more over its square where an edge crosses it: samples_per_pixel);
/// pixel (r, c) centre: x = (c + 0.5 - W/2) s, y = (H/2 - r - 0.5) s.
/// Row 0 is the +y edge, column 0 the -x edge; images are row-major.
///
/// A pixel holds the height z_C [m] of the first surface the ray meets coming down from
/// z = near: max { z of a surface point on the ray, z <= near }. Geometry above near is clipped
/// (not seen; a solid that reaches through near shows its underside, as with OpenGL's near
/// plane). Heights below far are clamped to far, and a pixel whose ray meets no surface at all
/// (excluded parts do not count) holds far.

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace climbsim::scene {

/// How depth images are computed. Both give the same image up to float rounding (a few µm on
/// the benchmark wall); services/scene/render/README.md has the measured speeds.
enum class DepthBackend {
  kRasterizer,  ///< z-buffer: triangles under the window projected to the pixel grid (default: about 4x faster)
  kEmbree,      ///< one Embree ray per pixel, packets of 16
};

/// "rasterizer" or "embree".
const char* toString(DepthBackend backend);

/// A set of pixels of a W x H image (e.g. the pixels a sealing shard can ever read): one byte
/// per pixel, and for culling which blocks of kBlockPx x kBlockPx pixels hold any of them.
class PixelMask {
 public:
  static constexpr int kBlockPx = 4;
  /// The pixels raster = row * W + col listed (each < W * H; any order, repeats allowed).
  PixelMask(int width_px, int height_px, const std::vector<std::uint32_t>& raster_pixels);
  int widthPx() const { return width_px_; }
  int heightPx() const { return height_px_; }
  std::size_t count() const { return count_; }  ///< distinct pixels in the set
  bool contains(int row, int col) const { return bytes_[static_cast<std::size_t>(row) * width_px_ + col] != 0; }
  /// 1 for a pixel in the set, else 0; W * H bytes, row-major.
  const std::uint8_t* bytes() const { return bytes_.data(); }
  /// Bytes readable after the last pixel's quad (0), so that a vector kernel may read 4 bytes
  /// from any pixel's.
  static constexpr int kQuadPadding = 3;
  /// The set over 2 x 2 pixels: bit 2 dr + dc of byte row * W + col set where pixel
  /// (row + dr, col + dc) is in it (dr, dc in {0, 1}); W * H bytes and kQuadPadding more (0).
  const std::uint8_t* quads() const { return quads_.data(); }
  /// Whether a block that meets rows r0..r1 and columns c0..c1 (clipped to the image) holds a
  /// pixel of the set: false means none of those pixels is in it (conservative: true may be).
  bool mayMeet(int r0, int r1, int c0, int c1) const;
  /// Whether rows r0..r1, columns c0..c1 (clipped to the image) hold a pixel of the set, exactly
  /// (from rowBits(): a word per 64 columns of a row those columns meet).
  bool meets(int r0, int r1, int c0, int c1) const;
  /// 64-bit words per row of rowBits(): (W + 63) / 64.
  int rowWords() const { return row_words_; }
  /// The set as bits: pixel (row, col) is bit col % 64 of word row * rowWords() + col / 64.
  const std::uint64_t* rowBits() const { return row_bits_.data(); }
  /// The blocks: (blocksY() + 1) x (blocksX() + 1) summed-area table of occupied blocks.
  const std::uint32_t* blockSums() const { return block_sum_.data(); }
  int blocksX() const { return blocks_x_; }
  int blocksY() const { return blocks_y_; }
  /// A maximal run of the set's pixels along one row: `length` pixels from raster index `raster` on.
  struct Run {
    std::uint32_t raster = 0;
    std::uint32_t length = 0;
  };
  /// The set as maximal row runs, in raster order (what a masked tile sends: idl/scene.idl
  /// DepthImage.mask_runs).
  const std::vector<Run>& runs() const { return runs_; }

 private:
  int width_px_ = 0, height_px_ = 0, blocks_x_ = 0, blocks_y_ = 0, row_words_ = 0;
  std::size_t count_ = 0;
  std::vector<std::uint8_t> bytes_;
  std::vector<std::uint8_t> quads_;       ///< W * H + kQuadPadding
  std::vector<std::uint64_t> row_bits_;   ///< H * row_words_
  std::vector<Run> runs_;
  std::vector<std::uint32_t> block_sum_;  ///< (blocks_y + 1) x (blocks_x + 1) summed-area table of occupied blocks
};

/// A rectangle of pixels of a depth image: rows row0 .. row0 + rows - 1, columns col0 ..
/// col0 + cols - 1. A tile of an image holds exactly the image's values there, bit for bit;
/// with a mask, only at the mask's pixels, and far at the tile's other pixels (they are not
/// rendered: a sealing shard's tile needs only the pixels its region can read).
struct PixelTile {
  int row0 = 0;
  int col0 = 0;
  int rows = 0;  ///< 0: the whole image (with cols = 0)
  int cols = 0;
  std::shared_ptr<const PixelMask> mask = nullptr;  ///< null: every pixel of the tile; else of the image's size
  bool whole() const { return rows == 0 && cols == 0; }
  bool operator==(const PixelTile& o) const {
    return row0 == o.row0 && col0 == o.col0 && rows == o.rows && cols == o.cols && mask == o.mask;
  }
};

/// Upper bound of width_px and height_px (idl/scene.idl).
constexpr int kMaxDepthImageSidePx = 2048;

/// Number of height levels of the 8-bit mode.
constexpr int kQuantisationLevels = 256;

/// Upper bound of DepthCameraParams::samples_per_pixel.
constexpr int kMaxSamplesPerPixel = 64;

/// The depth camera; defaults are the CROMSCI camera (256 x 256 px over 0.80 x 0.80 m,
/// near/far +-0.05 m about the sealing plane).
struct DepthCameraParams {
  int width_px = 256;                  ///< W, 1..1024
  int height_px = 256;                 ///< H, 1..1024
  double pixel_size_m = 0.80 / 256.0;  ///< edge s of a square pixel on the sealing plane [m], > 0
  double near_m = 0.05;                ///< highest height seen, z_C [m]; > far_m
  double far_m = -0.05;                ///< lowest height reported, z_C [m]
  /// true: heights are quantised to 256 levels over [far, near] (quantisedHeight()).
  bool quantised_8bit = false;
  /// n, 1..64. 1: every pixel holds its centre ray's height. n > 1: a pixel an edge of the
  /// wall crosses (area_sampling.hpp: its 3 x 3 centre heights bend by more than
  /// kEdgeThreshold_m) holds the mean of n rays through points of its square
  /// (subpixelOffsets(n)), its area-weighted height to 1/n of the pixel along each axis, so it
  /// follows an edge moving across the pixel; the others keep their centre's height.
  int samples_per_pixel = 1;
  /// With samples_per_pixel > 1: the sealing's max_slope [m/m] (>= 0), by which each edge pixel
  /// gets its support height h_sup = max_i (z_i - support_slope * |x_i - c|) over its samples
  /// (DepthImage::support_m, docs/design.md#sub-pixel-leakage); 0: no support heights.
  double support_slope = 0.0;
  /// Render only this part of the image (rasteriser only); whole by default.
  PixelTile tile;

  /// Throws climbsim::ConfigError naming the field and value when a value is out of range
  /// (a tile must lie inside the image).
  void validate() const;
  /// x_C of the centre of column col [m]: (col + 0.5 - W/2) s.
  double pixelCentreX_m(int col) const { return (col + 0.5 - 0.5 * width_px) * pixel_size_m; }
  /// y_C of the centre of row row [m]: (H/2 - row - 0.5) s.
  double pixelCentreY_m(int row) const { return (0.5 * height_px - row - 0.5) * pixel_size_m; }
};

/// One depth image: heights z_C [m] in [far_m, near_m], row-major, width_px * height_px values,
/// or, for a tile, tile.rows * tile.cols values of the tile's pixels.
struct DepthImage {
  int width_px = 0;
  int height_px = 0;
  PixelTile tile;  ///< whole() for a whole image
  double pixel_size_m = 0.0;
  double near_m = 0.0;
  double far_m = 0.0;
  bool quantised_8bit = false;
  /// No pixel of the image (of the whole image, also outside a tile) is higher than
  /// near_m - headroom_m [m], >= 0: 0 when only the camera's clamp at near is known; a tile
  /// chosen for the frame's geometry (SceneParams::depth_tile_for_bound) says its bound here.
  double headroom_m = 0.0;
  std::vector<float> height_m;
  /// Support heights of the edge pixels (DepthCameraParams::support_slope > 0): the raster
  /// index (row * width_px + col, ascending, pixels of the tile) of each edge pixel whose
  /// h_sup = max_i (z_i - support_slope * |x_i - c|) over its samples z_i at x_i (c its centre,
  /// at least far) lies above its height in height_m, and that h_sup [m]. The highest the
  /// sealing strip can be held at the pixel's centre by the wall inside its square.
  std::vector<std::uint32_t> support_px;
  std::vector<float> support_m;

  /// Height of image pixel (row, col) (inside the tile for a tile).
  float at(int row, int col) const {
    if (tile.whole()) return height_m[static_cast<std::size_t>(row) * width_px + col];
    return height_m[static_cast<std::size_t>(row - tile.row0) * tile.cols + (col - tile.col0)];
  }
};

/// The points of a pixel's square that samples_per_pixel = n samples, as offsets from its centre
/// in pixels along +column and +row, each in (-0.5, 0.5): an n-rooks pattern, point k at
/// ((k + 0.5) / n - 0.5, ((k m) mod n + 0.5) / n - 0.5) with m the integer coprime to n nearest
/// n / golden ratio. No two points share a column or a row offset, so an edge along the rows
/// or the columns changes the pixel's mean in steps of 1 / n of its height difference; the
/// offsets sum to 0, so a plane's mean is its height at the centre.
std::vector<std::pair<double, double>> subpixelOffsets(int n);

/// Height step of the 8-bit mode: Δ = (near - far) / 256 [m] (0.39 mm for the defaults).
inline double quantisationStep_m(double near_m, double far_m) { return (near_m - far_m) / kQuantisationLevels; }

/// Level of a height in the 8-bit mode: k = min(255, max(0, floor((h - far) / Δ))).
/// Levels truncate towards far, so a quantised height lies in (h - Δ, h]; far is level 0.
int quantisationLevel(double height_m, double near_m, double far_m);

/// Height of level k (0..255) in the 8-bit mode: far + k Δ [m]. Level 0 is far exactly (the
/// "nothing seen" value), level 128 is the sealing plane when near = -far, level 255 is near - Δ.
double quantisedHeight(int level, double near_m, double far_m);

/// Replaces every height of the image by quantisedHeight(quantisationLevel(h)) and sets
/// quantised_8bit.
void quantise8bit(DepthImage& image);

}  // namespace climbsim::scene
