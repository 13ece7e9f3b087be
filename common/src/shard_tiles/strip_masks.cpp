#include "climbsim/shard_tiles/strip_masks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::sealing {
namespace {

using Point = RobotGeometry::Point;

/// Distance from (x, y) to the line segment a-b [m].
double distanceToSegment_m(double x, double y, const Point& a, const Point& b) {
  const double dx = b.x_m - a.x_m;
  const double dy = b.y_m - a.y_m;
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0.0 ? ((x - a.x_m) * dx + (y - a.y_m) * dy) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(x - (a.x_m + t * dx), y - (a.y_m + t * dy));
}

}  // namespace

StripMasks::StripMasks(const RobotGeometry& geometry, const PixelGrid& grid, const std::string& source)
    : grid_(grid) {
  const std::size_t n_pixels = grid.pixelCount();
  const double half_width_m = geometry.strip_width_m / 2.0;
  const double half_x_m = grid.width_px * grid.pixel_size_m / 2.0;
  const double half_y_m = grid.height_px * grid.pixel_size_m / 2.0;
  segment_of_pixel_.assign(n_pixels, -1);
  std::vector<double> nearest_m(n_pixels, std::numeric_limits<double>::infinity());

  for (std::size_t s = 0; s < geometry.segments.size(); ++s) {
    const auto& seg = geometry.segments[s];
    for (const Point& p : seg.centreline_Robot) {
      if (std::abs(p.x_m) + half_width_m > half_x_m || std::abs(p.y_m) + half_width_m > half_y_m) {
        std::ostringstream why;
        why << source << ": sealing segment " << seg.name << " reaches (" << p.x_m << ", " << p.y_m
            << ") m +- " << half_width_m << " m, outside the camera's view of " << 2 * half_x_m << " x "
            << 2 * half_y_m << " m (" << grid.width_px << "x" << grid.height_px << " px of " << grid.pixel_size_m
            << " m): the sealing does not fit the depth image";
        throw ConfigError(why.str());
      }
    }
    // Distances to this segment only where its strip can reach: the bounding box of each
    // polyline piece grown by half a width.
    for (std::size_t k = 0; k + 1 < seg.centreline_Robot.size(); ++k) {
      const Point& a = seg.centreline_Robot[k];
      const Point& b = seg.centreline_Robot[k + 1];
      const int c0 = std::max(0, static_cast<int>(std::floor(grid.columnOfX(std::min(a.x_m, b.x_m) - half_width_m))));
      const int c1 = std::min(grid.width_px - 1,
                              static_cast<int>(std::ceil(grid.columnOfX(std::max(a.x_m, b.x_m) + half_width_m))));
      const int r0 = std::max(0, static_cast<int>(std::floor(grid.rowOfY(std::max(a.y_m, b.y_m) + half_width_m))));
      const int r1 = std::min(grid.height_px - 1,
                              static_cast<int>(std::ceil(grid.rowOfY(std::min(a.y_m, b.y_m) - half_width_m))));
      for (int r = r0; r <= r1; ++r) {
        const double y = grid.yOfRow_m(r);
        for (int c = c0; c <= c1; ++c) {
          const double d = distanceToSegment_m(grid.xOfColumn_m(c), y, a, b);
          const std::size_t i = static_cast<std::size_t>(r) * grid.width_px + c;
          // Segments come in index order, so a strict "<" leaves exact ties with the lower index.
          if (d <= half_width_m && d < nearest_m[i]) {
            nearest_m[i] = d;
            segment_of_pixel_[i] = static_cast<std::int16_t>(s);
          }
        }
      }
    }
  }

  segment_pixels_.assign(geometry.segments.size(), {});
  sealing_index_of_pixel_.assign(n_pixels, -1);
  for (std::size_t i = 0; i < n_pixels; ++i) {
    if (segment_of_pixel_[i] < 0) continue;
    const auto k = static_cast<std::uint32_t>(sealing_pixels_.size());
    sealing_index_of_pixel_[i] = static_cast<std::int32_t>(k);
    sealing_pixels_.push_back(static_cast<std::uint32_t>(i));
    segment_pixels_[segment_of_pixel_[i]].push_back(k);
  }
  for (std::size_t s = 0; s < segment_pixels_.size(); ++s) {
    if (segment_pixels_[s].empty()) {
      std::ostringstream why;
      why << source << ": sealing segment " << geometry.segments[s].name << " (strip width "
          << geometry.strip_width_m << " m) covers no pixel centre at pixel size " << grid.pixel_size_m
          << " m: the camera is too coarse for the strips";
      throw ConfigError(why.str());
    }
  }
}

}  // namespace climbsim::sealing
