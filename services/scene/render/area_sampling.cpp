#include "area_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace climbsim::scene {

namespace {

// Whether pixel (r, c) bends by more than the threshold in one of the four directions; a
// neighbour outside the image: the first difference instead.
bool bendsAtBorder(const std::vector<float>& centre_m, int width_px, int height_px, int r, int c, double threshold_m) {
  static constexpr int kDirections[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
  const auto at = [&](int row, int col) {
    return static_cast<double>(centre_m[static_cast<std::size_t>(row) * width_px + col]);
  };
  const auto inside = [&](int row, int col) { return row >= 0 && row < height_px && col >= 0 && col < width_px; };
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
  return edge;
}

}  // namespace

std::vector<std::uint32_t> edgePixels(const std::vector<float>& centre_m, int width_px, int height_px, int row0,
                                      int col0, int rows, int cols, const PixelMask* mask, double threshold_m,
                                      bool reference, RasterKernel kernel) {
  std::vector<std::uint32_t> edges;
  const BendingPixelsKernel bending = bendingPixelsKernel(kernel);
  std::vector<unsigned long long> bends(static_cast<std::size_t>(width_px) / 64 + 1);
  // Columns c0 .. c1 - 1 of row r (inside the tile): inner pixels (all eight neighbours in the
  // image) by the row kernel, the others one by one.
  const auto decide = [&](int r, int c0, int c1) {
    const auto border = [&](int from, int to) {
      for (int c = from; c < to; ++c) {
        if (bendsAtBorder(centre_m, width_px, height_px, r, c, threshold_m)) {
          edges.push_back(static_cast<std::uint32_t>(r) * static_cast<std::uint32_t>(width_px) + c);
        }
      }
    };
    const bool inner_row = !reference && r >= 1 && r + 1 < height_px;
    const int inner0 = inner_row ? std::max(c0, 1) : c1;
    const int inner1 = inner_row ? std::min(c1, width_px - 1) : c1;
    border(c0, inner0);
    if (inner0 < inner1) {
      const float* up = centre_m.data() + static_cast<std::size_t>(r - 1) * width_px;
      bending(up, up + width_px, up + 2 * width_px, inner0, inner1, threshold_m, bends.data());
      const std::uint32_t first = static_cast<std::uint32_t>(r) * static_cast<std::uint32_t>(width_px) + inner0;
      for (int word = 0; word < (inner1 - inner0 + 63) / 64; ++word) {
        for (unsigned long long bits = bends[word]; bits != 0; bits &= bits - 1) {
          edges.push_back(first + 64 * word + static_cast<std::uint32_t>(__builtin_ctzll(bits)));
        }
      }
    }
    border(inner1, c1);
  };
  if (mask == nullptr) {
    for (int r = row0; r < row0 + rows; ++r) decide(r, col0, col0 + cols);
    return edges;
  }
  // Only the mask's pixels: its row runs (raster order, so the edges stay ascending), cut to the tile.
  for (const PixelMask::Run& run : mask->runs()) {
    const int r = static_cast<int>(run.raster / static_cast<std::uint32_t>(width_px));
    if (r < row0 || r >= row0 + rows) continue;
    const int c = static_cast<int>(run.raster % static_cast<std::uint32_t>(width_px));
    const int c0 = std::max(c, col0);
    const int c1 = std::min(c + static_cast<int>(run.length), col0 + cols);
    if (c0 < c1) decide(r, c0, c1);
  }
  return edges;
}

std::pair<double, double> edgeNormal(const std::vector<float>& centre_m, int width_px, int height_px, int row,
                                     int col) {
  const auto at = [&](int dr, int dc) {
    const int r = std::clamp(row + dr, 0, height_px - 1);
    const int c = std::clamp(col + dc, 0, width_px - 1);
    return static_cast<double>(centre_m[static_cast<std::size_t>(r) * width_px + c]);
  };
  // Second differences: [[a, b], [b, d]] along +column and +row.
  const double h2 = 2.0 * at(0, 0);
  const double a = at(0, -1) - h2 + at(0, 1);
  const double d = at(-1, 0) - h2 + at(1, 0);
  const double b = (at(1, 1) - at(1, -1) - at(-1, 1) + at(-1, -1)) / 4.0;
  const double mid = (a + d) / 2.0, radius = std::hypot((a - d) / 2.0, b);
  const double lambda = std::abs(mid + radius) >= std::abs(mid - radius) ? mid + radius : mid - radius;
  // An eigenvector of lambda: (b, lambda - a) or (lambda - d, b), the longer of the two.
  const std::pair<double, double> u{b, lambda - a}, v{lambda - d, b};
  return std::hypot(u.first, u.second) >= std::hypot(v.first, v.second) ? u : v;
}

SupportBound::SupportBound(std::pair<double, double> normal, double slope, double pixel_m)
    : length_(std::hypot(normal.first, normal.second)),
      nx_(length_ > 0.0 ? normal.first / length_ : 0.0),
      ny_(length_ > 0.0 ? normal.second / length_ : 0.0),
      // The 8-connected distance to a line of unit normal n is the Euclidean one over n's extent
      // of the unit octagon (vertices along the axes and the diagonals).
      octagon_(std::max({std::abs(nx_), std::abs(ny_), (std::abs(nx_) + std::abs(ny_)) / std::sqrt(2.0)})),
      fall_m_per_px_(slope * pixel_m) {}

double SupportBound::at(const double* z_m, std::size_t count, const std::vector<std::pair<double, double>>& offsets,
                        std::pair<double, double> at) const {
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < count; ++i) {
    const double vx = offsets[i].first - at.first, vy = offsets[i].second - at.second;
    const double d_px = length_ > 0.0
                            ? std::abs(vx * nx_ + vy * ny_) / octagon_
                            : std::max(std::abs(vx), std::abs(vy)) + (std::sqrt(2.0) - 1.0) * std::min(std::abs(vx), std::abs(vy));
    top = std::max(top, z_m[i] - fall_m_per_px_ * d_px);
  }
  return top;
}

double supportHeight_m(const std::vector<double>& z_m, const std::vector<std::pair<double, double>>& offsets,
                       std::pair<double, double> normal, double slope, double pixel_m, std::pair<double, double> at) {
  return SupportBound(normal, slope, pixel_m).at(z_m.data(), z_m.size(), offsets, at);
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
