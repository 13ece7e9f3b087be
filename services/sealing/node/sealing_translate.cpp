#include "sealing_translate.hpp"

#include "height_screen.hpp"

#include <algorithm>
#include <limits>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace climbsim::sealing {
namespace {

/// The line `parts` make written to an ostream one after the other. A stream is only made for
/// a problem: it costs more than all the checks of a valid image.
template <class... Parts>
std::string problem(const Parts&... parts) {
  std::ostringstream why;
  (why << ... << parts);
  return why.str();
}

}  // namespace

PixelBox tileOf(const climbsim::DepthImage& sample) {
  if (sample.tile_rows() == 0 && sample.tile_cols() == 0) {
    return PixelBox{0, 0, static_cast<int>(sample.height_px()), static_cast<int>(sample.width_px())};
  }
  return PixelBox{static_cast<int>(sample.tile_row0()), static_cast<int>(sample.tile_col0()),
                  static_cast<int>(sample.tile_rows()), static_cast<int>(sample.tile_cols())};
}

std::string checkMaskRuns(const std::vector<std::uint32_t>& runs, int width_px, const PixelBox& tile,
                          std::size_t* pixels) {
  if (runs.size() % 2 != 0) return problem("mask_runs holds ", runs.size(), " values (a start and a length per run)");
  const auto w = static_cast<std::uint64_t>(width_px);
  std::uint64_t next = 0, count = 0;
  for (std::size_t k = 0; k < runs.size(); k += 2) {
    const std::uint64_t start = runs[k], length = runs[k + 1];
    const std::uint64_t row = start / w, col = start % w;
    const bool in_tile = length >= 1 && col + length <= w && row >= static_cast<std::uint64_t>(tile.row0) &&
                         row < static_cast<std::uint64_t>(tile.row0 + tile.rows) &&
                         col >= static_cast<std::uint64_t>(tile.col0) &&
                         col + length <= static_cast<std::uint64_t>(tile.col0 + tile.cols);
    if (!in_tile || start < next) {
      return problem("mask run ", k / 2, " (mask_runs[", k, "] = ", start, ", length ", length, ": row ", row, ", cols ",
                     col, "+", length, ") ",
                     in_tile ? "overlaps or precedes the run before it" : "does not lie along one row of the tile ",
                     in_tile ? "" : tile.text());
    }
    next = start + length;
    count += length;
  }
  if (pixels != nullptr) *pixels = static_cast<std::size_t>(count);
  return {};
}

bool maskRunsCover(const std::vector<std::uint32_t>& runs, const std::vector<std::uint32_t>& pixels) {
  std::size_t k = 0;
  for (const std::uint32_t p : pixels) {
    while (k < runs.size() && static_cast<std::uint64_t>(runs[k]) + runs[k + 1] <= p) k += 2;
    if (k >= runs.size() || runs[k] > p) return false;
  }
  return true;
}

std::size_t rasterOfValue(const climbsim::DepthImage& sample, const PixelBox& tile, std::size_t i) {
  const auto& runs = sample.mask_runs();
  if (runs.empty()) {
    return static_cast<std::size_t>(tile.row0 + static_cast<int>(i / static_cast<std::size_t>(tile.cols))) *
               sample.width_px() +
           static_cast<std::size_t>(tile.col0 + static_cast<int>(i % static_cast<std::size_t>(tile.cols)));
  }
  for (std::size_t k = 0; k + 1 < runs.size(); k += 2) {
    if (i < runs[k + 1]) return runs[k] + i;
    i -= runs[k + 1];
  }
  return 0;  // not reached for a sample that checkMaskRuns admitted
}

namespace {

/// "" if `sample`'s support heights are as idl/scene.idl says (as many indices as heights,
/// ascending, inside `tile`, each height finite in [low_m, high_m]), else one line naming the
/// first bad one; `top` is raised to the highest of them.
std::string checkSupports(const climbsim::DepthImage& sample, const PixelBox& tile, double low_m, double high_m,
                          float& top) {
  const auto& px = sample.support_px();
  const auto& v = sample.support_m();
  if (px.size() != v.size()) return problem(px.size(), " support pixels with ", v.size(), " support heights");
  const auto w = static_cast<std::uint32_t>(sample.width_px());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const auto row = static_cast<int>(px[i] / w);
    const auto col = static_cast<int>(px[i] % w);
    if ((i > 0 && px[i] <= px[i - 1]) || row < tile.row0 || row >= tile.row0 + tile.rows || col < tile.col0 ||
        col >= tile.col0 + tile.cols) {
      return problem("support_px[", i, "] = ", px[i], " (row ", row, ", col ", col, ") not ascending inside tile ",
                     tile.text());
    }
    if (!(v[i] >= low_m && v[i] <= high_m)) {
      return problem("support at pixel (row ", row, ", col ", col, ") support_m = ", v[i],
                     " outside [far_m, near_m - headroom_m] = [", sample.far_m(), ", ", heightBound_m(sample), "]");
    }
    top = std::max(top, v[i]);
  }
  return {};
}

}  // namespace

std::string checkDepthImage(const climbsim::DepthImage& sample, const PixelGrid& camera, float* highest) {
  if (!std::isfinite(sample.near_m()) || !std::isfinite(sample.far_m()) || !(sample.near_m() > sample.far_m())) {
    return problem("near_m = ", sample.near_m(), ", far_m = ", sample.far_m(), " (need finite near_m > far_m)");
  }
  if (!std::isfinite(sample.headroom_m()) || sample.headroom_m() < 0.0 ||
      !(heightBound_m(sample) >= sample.far_m())) {
    return problem("headroom_m = ", sample.headroom_m(), " (need 0 <= headroom_m <= near_m - far_m = ",
                   sample.near_m() - sample.far_m(), ")");
  }
  const PixelGrid g{static_cast<int>(sample.width_px()), static_cast<int>(sample.height_px()), sample.pixel_size_m()};
  const std::string grid_problem = checkPixelGrid(g, camera);
  if (!grid_problem.empty()) return grid_problem;
  const PixelBox tile = tileOf(sample);
  if (tile.rows < 1 || tile.cols < 1 || !PixelBox{0, 0, g.height_px, g.width_px}.contains(tile)) {
    return problem("tile rows ", sample.tile_row0(), "+", sample.tile_rows(), ", columns ", sample.tile_col0(), "+",
                   sample.tile_cols(), " does not lie in the ", g.width_px, "x", g.height_px, " px image");
  }
  const auto& h = sample.height_m();
  std::size_t expected = static_cast<std::size_t>(tile.rows) * static_cast<std::size_t>(tile.cols);
  if (!sample.mask_runs().empty()) {
    const std::string bad_runs = checkMaskRuns(sample.mask_runs(), g.width_px, tile, &expected);
    if (!bad_runs.empty()) return bad_runs;
  }
  if (h.size() != expected) {
    if (sample.mask_runs().empty()) return problem(h.size(), " heights for a tile of ", tile.cols, "x", tile.rows, " px");
    return problem(h.size(), " heights for ", sample.mask_runs().size() / 2, " mask runs of ", expected, " px");
  }
  // The camera clamps to [far, near]; 1 µm covers float rounding of the bounds.
  constexpr double kTolerance_m = 1e-6;
  const double far_m = sample.far_m();
  const double near_m = heightBound_m(sample);
  const double low_m = far_m - kTolerance_m;
  const double high_m = near_m + kTolerance_m;
  // One pass over every pixel, in float: low_f is the least float >= low_m and high_f the
  // greatest float <= high_m, so a float v passes (low_f <= v <= high_f) exactly when
  // low_m <= v <= high_m in double (NaN and infinities fail). It only screens: on a failure the
  // exact loop below names the first bad pixel, the same line as ever.
  float low_f = static_cast<float>(low_m);
  if (static_cast<double>(low_f) < low_m) low_f = std::nextafter(low_f, std::numeric_limits<float>::infinity());
  float high_f = static_cast<float>(high_m);
  if (static_cast<double>(high_f) > high_m) high_f = std::nextafter(high_f, -std::numeric_limits<float>::infinity());
  float top = -std::numeric_limits<float>::infinity();
  const bool all_ok = screenHeights(h.data(), h.size(), low_f, high_f, top);
  if (all_ok) {
    const std::string bad_support = checkSupports(sample, tile, low_m, high_m, top);
    if (highest != nullptr) *highest = top;
    return bad_support;
  }
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (!std::isfinite(h[i])) return nonFinitePixel(camera, rasterOfValue(sample, tile, i), h[i]);
    if (h[i] < low_m || h[i] > high_m) {
      const std::size_t raster = rasterOfValue(sample, tile, i);
      return problem("pixel (row ", raster / static_cast<std::size_t>(camera.width_px), ", col ",
                     raster % static_cast<std::size_t>(camera.width_px), ") height_m = ", h[i], " outside [far_m, near_m",
                     sample.headroom_m() > 0.0 ? " - headroom_m" : "", "] = [", far_m, ", ", near_m, "]");
    }
  }
  if (highest != nullptr) *highest = top;  // not reached: the screen fails only on a bad pixel
  return {};
}

namespace {

/// Places `sample`'s pixels into `depth` (see depthGridFromIdl); when `take` is the sample
/// itself (ours to empty), its support heights and a whole image's pixels are swapped in
/// (`take` is left with depth's old buffers), else copied.
void placeDepthImage(const climbsim::DepthImage& sample, DepthGrid& depth, climbsim::DepthImage* take) {
  const PixelGrid grid{static_cast<int>(sample.width_px()), static_cast<int>(sample.height_px()), sample.pixel_size_m()};
  const PixelBox tile = tileOf(sample);
  const auto& h = sample.height_m();
  // Supports of the sample's pixels only: a tile's reader reads no other pixel.
  if (take != nullptr) {
    depth.supports.raster.swap(take->support_px());
    depth.supports.height_m.swap(take->support_m());
  } else {
    depth.supports.raster = sample.support_px();
    depth.supports.height_m = sample.support_m();
  }
  if (tile == PixelBox{0, 0, grid.height_px, grid.width_px} && sample.mask_runs().empty()) {
    depth.grid = grid;
    if (take != nullptr) {
      depth.height_m.swap(take->height_m());
    } else {
      depth.height_m = h;
    }
  } else {
    if (!(depth.grid == grid) || depth.height_m.size() != grid.pixelCount()) {
      depth.grid = grid;
      depth.height_m.assign(grid.pixelCount(), static_cast<float>(sample.far_m()));
    }
    const auto& runs = sample.mask_runs();
    if (!runs.empty()) {
      auto from = h.begin();
      for (std::size_t k = 0; k + 1 < runs.size(); k += 2) {
        std::copy_n(from, runs[k + 1], depth.height_m.begin() + static_cast<std::ptrdiff_t>(runs[k]));
        from += static_cast<std::ptrdiff_t>(runs[k + 1]);
      }
      return;
    }
    for (int r = 0; r < tile.rows; ++r) {
      std::copy_n(h.begin() + static_cast<std::ptrdiff_t>(r) * tile.cols, tile.cols,
                  depth.height_m.begin() + static_cast<std::ptrdiff_t>(tile.row0 + r) * grid.width_px + tile.col0);
    }
  }
}

}  // namespace

void depthGridFromIdl(const climbsim::DepthImage& sample, DepthGrid& depth) {
  placeDepthImage(sample, depth, nullptr);
  // The highest pixel received bounds how far a shard's region must reach: pixels outside a
  // tile that covers the shard's neededBox lie beyond the reach of any height up to near.
  float highest = -std::numeric_limits<float>::infinity();
  for (const float v : sample.height_m()) highest = std::max(highest, v);
  for (const float v : sample.support_m()) highest = std::max(highest, v);
  depth.upper_bound_m = highest;
}

void depthGridFromIdl(climbsim::DepthImage&& sample, DepthGrid& depth, float highest) {
  placeDepthImage(sample, depth, &sample);
  depth.upper_bound_m = highest;
}

DepthGrid depthGridFromIdl(const climbsim::DepthImage& sample) {
  DepthGrid depth;
  depthGridFromIdl(sample, depth);
  return depth;
}

climbsim::DepthImage depthImageToIdl(const DepthGrid& depth, double far_m, double near_m) {
  climbsim::DepthImage sample;
  sample.width_px(static_cast<std::uint32_t>(depth.grid.width_px));
  sample.height_px(static_cast<std::uint32_t>(depth.grid.height_px));
  sample.pixel_size_m(depth.grid.pixel_size_m);
  sample.near_m(near_m);
  sample.far_m(far_m);
  sample.quantised_8bit(false);
  sample.tile_rows(static_cast<std::uint32_t>(depth.grid.height_px));
  sample.tile_cols(static_cast<std::uint32_t>(depth.grid.width_px));
  sample.height_m(depth.height_m);
  sample.support_px(depth.supports.raster);
  sample.support_m(depth.supports.height_m);
  return sample;
}

climbsim::Leakage leakageToIdl(const std::vector<std::string>& names, const std::vector<SegmentLeak>& leaks,
                               const std::vector<std::size_t>& indices) {
  if (indices.size() > 64) throw std::invalid_argument("Leakage holds at most 64 segments");
  climbsim::Leakage sample;
  sample.segments().reserve(indices.size());
  for (const std::size_t i : indices) {
    if (names.at(i).size() > 31) throw std::invalid_argument("segment name '" + names[i] + "' longer than 31");
    climbsim::LeakageSegment s;
    s.segment(names[i]);
    s.leak_area_m2(leaks.at(i).leak_area_m2);
    s.mean_gap_m(leaks.at(i).mean_gap_m);
    s.no_surface_share(leaks.at(i).no_surface_share);
    sample.segments().push_back(std::move(s));
  }
  return sample;
}

climbsim::SealingImage sealingImageToIdl(const std::string& source, std::uint64_t step, std::int64_t t_ns,
                                         const std::string& kind, const std::vector<unsigned char>& png) {
  climbsim::SealingImage sample;
  sample.source(source);
  sample.step(step);
  sample.t_ns(t_ns);
  sample.kind(kind);
  sample.png(png);
  return sample;
}

}  // namespace climbsim::sealing
