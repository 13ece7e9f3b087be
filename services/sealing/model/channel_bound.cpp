#include "channel_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace climbsim::sealing {
namespace {

/// Side of point (x, y) of the polyline `line`: 0 left of its nearest edge, 1 right.
int sideOf(const std::vector<RobotGeometry::Point>& line, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  int side = 0;
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const double ax = line[k].x_m, ay = line[k].y_m;
    const double dx = line[k + 1].x_m - ax, dy = line[k + 1].y_m - ay;
    const double len2 = dx * dx + dy * dy;
    const double t = len2 > 0.0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    const double px = ax + t * dx - x, py = ay + t * dy - y;
    const double d2 = px * px + py * py;
    if (d2 < best) {
      best = d2;
      side = dx * (y - ay) - dy * (x - ax) >= 0.0 ? 0 : 1;
    }
  }
  return side;
}

}  // namespace

StripEdges::StripEdges(const RobotGeometry& geometry, const StripMasks& masks) : edges_(masks.segmentCount()) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  for (std::uint32_t k = 0; k < pixels.size(); ++k) {
    const std::size_t raster = pixels[k];
    const int r = static_cast<int>(raster / static_cast<std::size_t>(g.width_px));
    const int c = static_cast<int>(raster % static_cast<std::size_t>(g.width_px));
    const int segment = masks.segmentOfPixel(raster);
    std::array<bool, 2> borders{false, false};
    const int dr[4] = {-1, 1, 0, 0}, dc[4] = {0, 0, -1, 1};
    for (int n = 0; n < 4; ++n) {
      const int rn = r + dr[n], cn = c + dc[n];
      if (rn < 0 || cn < 0 || rn >= g.height_px || cn >= g.width_px) continue;
      if (masks.segmentOfPixel(static_cast<std::size_t>(rn) * g.width_px + cn) >= 0) continue;
      borders[static_cast<std::size_t>(
          sideOf(geometry.segments[static_cast<std::size_t>(segment)].centreline_Robot, g.xOfColumn_m(cn), g.yOfRow_m(rn)))] =
          true;
    }
    for (int side = 0; side < 2; ++side) {
      if (borders[static_cast<std::size_t>(side)]) edges_[static_cast<std::size_t>(segment)][static_cast<std::size_t>(side)].push_back(k);
    }
  }
}

double StripEdges::channelArea_m2(const StripMasks& masks, std::size_t segment, double length_m,
                                  const std::vector<float>& ground_m, const std::vector<double>& sealing_m) const {
  const auto& pixels = masks.sealingPixels();
  std::array<double, 2> area{0.0, 0.0};
  for (int side = 0; side < 2; ++side) {
    const auto& edge = edges_[segment][static_cast<std::size_t>(side)];
    if (edge.empty()) continue;  // no side open to anything: no channel
    double sum_m = 0.0;
    for (const std::uint32_t k : edge) sum_m += sealing_m[k] - static_cast<double>(ground_m[pixels[k]]);
    area[static_cast<std::size_t>(side)] = length_m * sum_m / static_cast<double>(edge.size());
  }
  return std::min(area[0], area[1]);
}

}  // namespace climbsim::sealing
