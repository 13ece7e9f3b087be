#include "area_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::scene {

std::vector<std::uint32_t> edgePixels(const std::vector<float>& centre_m, int width_px, int height_px, int row0,
                                      int col0, int rows, int cols, const PixelMask* mask, double threshold_m) {
  static constexpr int kDirections[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
  const auto at = [&](int r, int c) {
    return static_cast<double>(centre_m[static_cast<std::size_t>(r) * width_px + c]);
  };
  const auto inside = [&](int r, int c) { return r >= 0 && r < height_px && c >= 0 && c < width_px; };
  std::vector<std::uint32_t> edges;
  for (int r = row0; r < row0 + rows; ++r) {
    for (int c = col0; c < col0 + cols; ++c) {
      if (mask && !mask->contains(r, c)) continue;
      const double h = at(r, c);
      bool edge = false;
      for (const auto& d : kDirections) {
        const bool before = inside(r - d[0], c - d[1]);
        const bool after = inside(r + d[0], c + d[1]);
        double change = 0.0;
        if (before && after) {
          change = at(r - d[0], c - d[1]) - 2.0 * h + at(r + d[0], c + d[1]);
        } else if (before || after) {
          change = before ? at(r - d[0], c - d[1]) - h : at(r + d[0], c + d[1]) - h;
        }
        edge = edge || std::abs(change) > threshold_m;
      }
      if (edge) edges.push_back(static_cast<std::uint32_t>(r) * static_cast<std::uint32_t>(width_px) + c);
    }
  }
  return edges;
}

std::shared_ptr<const PixelMask> dilatedMask(const PixelMask& mask) {
  const int W = mask.widthPx();
  const int H = mask.heightPx();
  std::vector<std::uint8_t> grown(static_cast<std::size_t>(W) * H, 0);
  for (const PixelMask::Run& run : mask.runs()) {
    const int row = static_cast<int>(run.raster / static_cast<std::uint32_t>(W));
    const int col = static_cast<int>(run.raster % static_cast<std::uint32_t>(W));
    const int c0 = std::max(0, col - 1), c1 = std::min(W - 1, col + static_cast<int>(run.length));
    for (int r = std::max(0, row - 1); r <= std::min(H - 1, row + 1); ++r) {
      std::fill(grown.begin() + static_cast<std::ptrdiff_t>(r) * W + c0,
                grown.begin() + static_cast<std::ptrdiff_t>(r) * W + c1 + 1, std::uint8_t{1});
    }
  }
  std::vector<std::uint32_t> pixels;
  for (std::size_t i = 0; i < grown.size(); ++i) {
    if (grown[i] != 0) pixels.push_back(static_cast<std::uint32_t>(i));
  }
  return std::make_shared<const PixelMask>(W, H, pixels);
}

PixelTile tileOf(int width_px, int height_px, const std::vector<std::uint32_t>& raster_pixels) {
  int r0 = height_px, r1 = -1, c0 = width_px, c1 = -1;
  for (const std::uint32_t i : raster_pixels) {
    const int r = static_cast<int>(i / static_cast<std::uint32_t>(width_px));
    const int c = static_cast<int>(i % static_cast<std::uint32_t>(width_px));
    r0 = std::min(r0, r);
    r1 = std::max(r1, r);
    c0 = std::min(c0, c);
    c1 = std::max(c1, c);
  }
  PixelTile tile;
  tile.row0 = r0;
  tile.col0 = c0;
  tile.rows = r1 - r0 + 1;
  tile.cols = c1 - c0 + 1;
  tile.mask = std::make_shared<const PixelMask>(width_px, height_px, raster_pixels);
  return tile;
}

}  // namespace climbsim::scene
