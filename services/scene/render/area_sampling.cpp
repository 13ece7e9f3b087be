#include "area_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
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

// Whether inner pixel c of a row bends (rows up, mid, down; all eight neighbours in the image).
bool bendsInside(const float* up, const float* mid, const float* down, int c, double threshold_m) {
  const double h2 = 2.0 * static_cast<double>(mid[c]);
  const double along_row = static_cast<double>(mid[c - 1]) - h2 + static_cast<double>(mid[c + 1]);
  const double along_col = static_cast<double>(up[c]) - h2 + static_cast<double>(down[c]);
  const double diagonal = static_cast<double>(up[c - 1]) - h2 + static_cast<double>(down[c + 1]);
  const double antidiagonal = static_cast<double>(up[c + 1]) - h2 + static_cast<double>(down[c - 1]);
  return (std::abs(along_row) > threshold_m) | (std::abs(along_col) > threshold_m) |
         (std::abs(diagonal) > threshold_m) | (std::abs(antidiagonal) > threshold_m);
}

constexpr int kBendLanes = 4;  // one SSE2 register of floats
using BendFloats = float __attribute__((vector_size(4 * kBendLanes)));
using BendMask = int __attribute__((vector_size(4 * kBendLanes)));  // a comparison's lanes: 0 or -1

// bendsInside for pixels c .. c + kBendLanes - 1, the same decisions: each second difference in
// float first, E = a - 2h + b rounded twice, |float - double| <= 2^-22 (|a| + 2|h| + |b|)
// <= 2^-20 m for m the largest |height| of the 3 x 3 neighbourhood; the largest |E| of the four
// decides where it lies clear of the threshold by a far wider margin (2^-18 m and 2^-10 of the
// threshold), bendsInside the rest (and anything not finite).
void bendsInsideRun(const float* up, const float* mid, const float* down, int c, double threshold_m,
                    unsigned char* bends) {
  const auto magnitude = [](BendFloats x) { return x < 0.0f ? -x : x; };  // |x| (the sign is all that differs)
  const auto larger = [](BendFloats x, BendFloats y) { return x > y ? x : y; };
  BendFloats h[3][3];  // h[row][column] at rows up, mid, down and columns c - 1, c, c + 1
  const float* const rows[3] = {up, mid, down};
  BendFloats largest_height{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      __builtin_memcpy(&h[i][j], rows[i] + c - 1 + j, sizeof(BendFloats));
      largest_height = larger(largest_height, magnitude(h[i][j]));
    }
  }
  const BendFloats h2 = 2.0f * h[1][1];
  BendFloats largest_change = magnitude(h[1][0] - h2 + h[1][2]);
  largest_change = larger(largest_change, magnitude(h[0][1] - h2 + h[2][1]));
  largest_change = larger(largest_change, magnitude(h[0][0] - h2 + h[2][2]));
  largest_change = larger(largest_change, magnitude(h[0][2] - h2 + h[2][0]));
  const auto threshold = static_cast<float>(threshold_m);
  const BendFloats margin = 0x1p-18f * largest_height + 0x1p-10f * threshold;
  const BendMask surely_bends = largest_change > threshold + margin;
  const BendMask surely_flat = largest_change < threshold - margin;
  for (int k = 0; k < kBendLanes; ++k) {
    bends[c + k] = surely_bends[k] != 0  ? 1
                   : surely_flat[k] != 0 ? 0
                                         : static_cast<unsigned char>(bendsInside(up, mid, down, c + k, threshold_m));
  }
}

}  // namespace

std::vector<std::uint32_t> edgePixels(const std::vector<float>& centre_m, int width_px, int height_px, int row0,
                                      int col0, int rows, int cols, const PixelMask* mask, double threshold_m,
                                      bool reference) {
  std::vector<std::uint32_t> edges;
  std::vector<unsigned char> bends(static_cast<std::size_t>(width_px));
  // Columns c0 .. c1 - 1 of row r (inside the tile): inner pixels (all eight neighbours in the
  // image) with the border's expressions in a loop without branches, the others one by one.
  const auto decide = [&](int r, int c0, int c1) {
    const bool inner_row = !reference && r >= 1 && r + 1 < height_px;
    const int inner0 = inner_row ? std::max(c0, 1) : c1;
    const int inner1 = inner_row ? std::min(c1, width_px - 1) : c1;
    if (inner0 < inner1) {
      const float* up = centre_m.data() + static_cast<std::size_t>(r - 1) * width_px;
      const float* mid = up + width_px;
      const float* down = mid + width_px;
      int c = inner0;
      for (; c + kBendLanes <= inner1; c += kBendLanes) bendsInsideRun(up, mid, down, c, threshold_m, bends.data());
      for (; c < inner1; ++c) bends[c] = static_cast<unsigned char>(bendsInside(up, mid, down, c, threshold_m));
    }
    for (int c = c0; c < c1; ++c) {
      if (c >= inner0 && c + 8 <= inner1) {  // eight flat inner pixels at once
        std::uint64_t eight = 0;
        std::memcpy(&eight, &bends[c], sizeof(eight));
        if (eight == 0) {
          c += 7;
          continue;
        }
      }
      const bool edge = c >= inner0 && c < inner1 ? bends[c] != 0
                                                  : bendsAtBorder(centre_m, width_px, height_px, r, c, threshold_m);
      if (edge) edges.push_back(static_cast<std::uint32_t>(r) * static_cast<std::uint32_t>(width_px) + c);
    }
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
