#include "depth_camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <sstream>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::scene {

const char* toString(DepthBackend backend) {
  return backend == DepthBackend::kEmbree ? "embree" : "rasterizer";
}

namespace {

template <typename T>
[[noreturn]] void badValue(const char* key, T value, const char* requirement) {
  std::ostringstream msg;
  msg << "depth camera: " << key << " = " << value << ": " << requirement;
  throw ConfigError(msg.str());
}

}  // namespace

void DepthCameraParams::validate() const {
  if (width_px < 1 || width_px > kMaxDepthImageSidePx) badValue("width_px", width_px, "must be in 1..2048");
  if (height_px < 1 || height_px > kMaxDepthImageSidePx) badValue("height_px", height_px, "must be in 1..2048");
  if (!std::isfinite(pixel_size_m) || pixel_size_m <= 0.0) badValue("pixel_size_m", pixel_size_m, "must be > 0");
  if (!std::isfinite(near_m)) badValue("near_m", near_m, "must be finite");
  if (!std::isfinite(far_m)) badValue("far_m", far_m, "must be finite");
  if (!(near_m > far_m)) badValue("near_m", near_m, ("must be > far_m = " + std::to_string(far_m)).c_str());
  if (samples_per_pixel < 1 || samples_per_pixel > kMaxSamplesPerPixel) {
    badValue("samples_per_pixel", samples_per_pixel, "must be in 1..64");
  }
  if (!(support_slope >= 0.0) || !std::isfinite(support_slope)) {
    badValue("support_slope", support_slope, "must be finite and >= 0");
  }
  if (tile.mask && (tile.mask->widthPx() != width_px || tile.mask->heightPx() != height_px)) {
    badValue("tile.mask", std::to_string(tile.mask->widthPx()) + " x " + std::to_string(tile.mask->heightPx()) + " px",
             "a tile's mask must have the image's size");
  }
  if (!tile.whole()) {
    if (tile.rows < 1 || tile.cols < 1) badValue("tile.rows", tile.rows < 1 ? tile.rows : tile.cols, "a tile needs >= 1 row and column");
    if (tile.row0 < 0 || tile.row0 + tile.rows > height_px) badValue("tile.row0", tile.row0, "the tile's rows must lie in the image");
    if (tile.col0 < 0 || tile.col0 + tile.cols > width_px) badValue("tile.col0", tile.col0, "the tile's columns must lie in the image");
  }
}

std::vector<std::pair<double, double>> subpixelOffsets(int n) {
  // m: coprime to n, nearest n / golden ratio (the smaller of two equally near).
  const double target = n / ((1.0 + std::sqrt(5.0)) / 2.0);
  int m = 1;
  for (int c = 1; c < std::max(n, 2); ++c) {
    if (std::gcd(c, n) == 1 && std::abs(c - target) < std::abs(m - target)) m = c;
  }
  std::vector<std::pair<double, double>> offsets;
  for (int k = 0; k < n; ++k) {
    offsets.emplace_back((k + 0.5) / n - 0.5, ((k * m) % n + 0.5) / n - 0.5);
  }
  return offsets;
}

PixelMask::PixelMask(int width_px, int height_px, const std::vector<std::uint32_t>& raster_pixels)
    : width_px_(width_px),
      height_px_(height_px),
      blocks_x_((width_px + kBlockPx - 1) / kBlockPx),
      blocks_y_((height_px + kBlockPx - 1) / kBlockPx),
      row_words_((width_px + 63) / 64),
      bytes_(static_cast<std::size_t>(width_px) * height_px, 0),
      quads_(bytes_.size() + kQuadPadding, 0),
      row_bits_(static_cast<std::size_t>(row_words_) * height_px, 0) {
  std::vector<std::uint8_t> occupied(static_cast<std::size_t>(blocks_x_) * blocks_y_, 0);
  for (const std::uint32_t raster : raster_pixels) {
    if (raster >= bytes_.size()) badValue("mask pixel", raster, "must lie in the image");
    count_ += bytes_[raster] == 0;
    bytes_[raster] = 1;
    const int row = static_cast<int>(raster / static_cast<std::uint32_t>(width_px));
    const int col = static_cast<int>(raster % static_cast<std::uint32_t>(width_px));
    occupied[static_cast<std::size_t>(row / kBlockPx) * blocks_x_ + col / kBlockPx] = 1;
    row_bits_[static_cast<std::size_t>(row) * row_words_ + col / 64] |= std::uint64_t{1} << (col % 64);
    // The quads whose 2 x 2 pixels hold this one: those from (row - dr, col - dc).
    for (int dr = 0; dr <= std::min(row, 1); ++dr) {
      for (int dc = 0; dc <= std::min(col, 1); ++dc) {
        quads_[raster - static_cast<std::uint32_t>(dr * width_px + dc)] |= static_cast<std::uint8_t>(1u << (2 * dr + dc));
      }
    }
  }
  block_sum_.assign(static_cast<std::size_t>(blocks_x_ + 1) * (blocks_y_ + 1), 0);
  for (int by = 0; by < blocks_y_; ++by) {
    for (int bx = 0; bx < blocks_x_; ++bx) {
      const auto at = [&](int y, int x) -> std::uint32_t& { return block_sum_[static_cast<std::size_t>(y) * (blocks_x_ + 1) + x]; };
      at(by + 1, bx + 1) = occupied[static_cast<std::size_t>(by) * blocks_x_ + bx] + at(by, bx + 1) + at(by + 1, bx) - at(by, bx);
    }
  }
  // The row runs from the bits, a word (64 pixels) at a time: a run starts at the first set bit
  // from `col` on and ends at the next clear one (the bits past W are clear).
  for (int row = 0; row < height_px; ++row) {
    const std::uint64_t* bits = row_bits_.data() + static_cast<std::size_t>(row) * row_words_;
    const auto next = [&](int col, bool set) {
      int w = col / 64;
      std::uint64_t word = (set ? bits[w] : ~bits[w]) & (~std::uint64_t{0} << (col % 64));
      while (word == 0 && ++w < row_words_) word = set ? bits[w] : ~bits[w];
      return w < row_words_ ? std::min(width_px, w * 64 + __builtin_ctzll(word)) : width_px;
    };
    for (int col = next(0, true); col < width_px;) {
      const int end = next(col, false);
      runs_.push_back({static_cast<std::uint32_t>(row * width_px + col), static_cast<std::uint32_t>(end - col)});
      col = end < width_px ? next(end, true) : width_px;
    }
  }
}

namespace {

// Rows r0..r1 and columns c0..c1 clipped to a W x H image; false where nothing is left.
bool clipToImage(int& r0, int& r1, int& c0, int& c1, int width_px, int height_px) {
  r0 = std::max(r0, 0);
  c0 = std::max(c0, 0);
  r1 = std::min(r1, height_px - 1);
  c1 = std::min(c1, width_px - 1);
  return r0 <= r1 && c0 <= c1;
}

}  // namespace

bool PixelMask::mayMeet(int r0, int r1, int c0, int c1) const {
  if (!clipToImage(r0, r1, c0, c1, width_px_, height_px_)) return false;
  const int y0 = r0 / kBlockPx, y1 = r1 / kBlockPx + 1, x0 = c0 / kBlockPx, x1 = c1 / kBlockPx + 1;
  const auto at = [&](int y, int x) { return block_sum_[static_cast<std::size_t>(y) * (blocks_x_ + 1) + x]; };
  return at(y1, x1) - at(y0, x1) - at(y1, x0) + at(y0, x0) > 0;
}

bool PixelMask::meets(int r0, int r1, int c0, int c1) const {
  if (!clipToImage(r0, r1, c0, c1, width_px_, height_px_)) return false;
  const int w0 = c0 / 64, w1 = c1 / 64;
  // Columns c0..c1 within the first and the last word (the same word when w0 = w1).
  const std::uint64_t first = ~std::uint64_t{0} << (c0 % 64);
  const std::uint64_t last = ~std::uint64_t{0} >> (63 - c1 % 64);
  for (int r = r0; r <= r1; ++r) {
    const std::uint64_t* row = row_bits_.data() + static_cast<std::size_t>(r) * row_words_;
    if (w0 == w1) {
      if ((row[w0] & first & last) != 0) return true;
      continue;
    }
    if ((row[w0] & first) != 0 || (row[w1] & last) != 0) return true;
    for (int w = w0 + 1; w < w1; ++w) {
      if (row[w] != 0) return true;
    }
  }
  return false;
}

int quantisationLevel(double height_m, double near_m, double far_m) {
  const double k = std::floor((height_m - far_m) / quantisationStep_m(near_m, far_m));
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(kQuantisationLevels - 1)));
}

double quantisedHeight(int level, double near_m, double far_m) {
  return far_m + level * quantisationStep_m(near_m, far_m);
}

void quantise8bit(DepthImage& image) {
  for (float& h : image.height_m) {
    h = static_cast<float>(quantisedHeight(quantisationLevel(h, image.near_m, image.far_m), image.near_m, image.far_m));
  }
  image.quantised_8bit = true;
}

}  // namespace climbsim::scene
