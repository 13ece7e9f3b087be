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

/// Rows r0..r1 and columns c0..c1 of the grid (clipped to it).
struct Box {
  int r0, r1, c0, c1;
};

/// The pixels within the bounding box of the piece a-b grown by `reach_m`.
Box boxAround(const PixelGrid& grid, const Point& a, const Point& b, double reach_m) {
  Box box{};
  box.c0 = std::max(0, static_cast<int>(std::floor(grid.columnOfX(std::min(a.x_m, b.x_m) - reach_m))));
  box.c1 = std::min(grid.width_px - 1, static_cast<int>(std::ceil(grid.columnOfX(std::max(a.x_m, b.x_m) + reach_m))));
  box.r0 = std::max(0, static_cast<int>(std::floor(grid.rowOfY(std::max(a.y_m, b.y_m) + reach_m))));
  box.r1 = std::min(grid.height_px - 1, static_cast<int>(std::ceil(grid.rowOfY(std::min(a.y_m, b.y_m) - reach_m))));
  return box;
}

}  // namespace

StripMasks::StripMasks(const RobotGeometry& geometry, const PixelGrid& grid, const std::string& source,
                       StripOutline outline)
    : grid_(grid), outline_(outline) {
  const double half_width_m = geometry.strip_width_m / 2.0;
  const double half_x_m = grid.width_px * grid.pixel_size_m / 2.0;
  const double half_y_m = grid.height_px * grid.pixel_size_m / 2.0;
  for (const auto& seg : geometry.segments) {
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
  }
  segment_of_pixel_.assign(grid.pixelCount(), -1);
  sealing_index_of_pixel_.assign(grid.pixelCount(), -1);
  segment_pixels_.assign(geometry.segments.size(), {});
  leak_pixels_.assign(geometry.segments.size(), {});
  leak_shares_.assign(geometry.segments.size(), {});
  share_sum_.assign(geometry.segments.size(), 0.0);
  if (outline == StripOutline::kPixelCentres) {
    outlineByCentres(geometry);
  } else {
    outlineByShares(geometry);
  }
  for (std::size_t s = 0; s < segment_pixels_.size(); ++s) {
    if (segment_pixels_[s].empty()) {
      std::ostringstream why;
      why << source << ": sealing segment " << geometry.segments[s].name << " (strip width "
          << geometry.strip_width_m << " m) covers no pixel "
          << (outline == StripOutline::kPixelCentres ? "centre " : "") << "at pixel size " << grid.pixel_size_m
          << " m: the camera is too coarse for the strips";
      throw ConfigError(why.str());
    }
  }
}

void StripMasks::outlineByCentres(const RobotGeometry& geometry) {
  const PixelGrid& grid = grid_;
  const std::size_t n_pixels = grid.pixelCount();
  const double half_width_m = geometry.strip_width_m / 2.0;
  std::vector<double> nearest_m(n_pixels, std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < geometry.segments.size(); ++s) {
    const auto& seg = geometry.segments[s];
    // Distances to this segment only where its strip can reach: the bounding box of each
    // polyline piece grown by half a width.
    for (std::size_t k = 0; k + 1 < seg.centreline_Robot.size(); ++k) {
      const Point& a = seg.centreline_Robot[k];
      const Point& b = seg.centreline_Robot[k + 1];
      const Box box = boxAround(grid, a, b, half_width_m);
      for (int r = box.r0; r <= box.r1; ++r) {
        const double y = grid.yOfRow_m(r);
        for (int c = box.c0; c <= box.c1; ++c) {
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
  for (std::size_t i = 0; i < n_pixels; ++i) {
    const int s = segment_of_pixel_[i];
    if (s < 0) continue;
    const auto k = static_cast<std::uint32_t>(sealing_pixels_.size());
    sealing_index_of_pixel_[i] = static_cast<std::int32_t>(k);
    sealing_pixels_.push_back(static_cast<std::uint32_t>(i));
    segment_pixels_[static_cast<std::size_t>(s)].push_back(k);
    // A whole pixel of its segment.
    leak_pixels_[static_cast<std::size_t>(s)].push_back(k);
    leak_shares_[static_cast<std::size_t>(s)].push_back(1.0);
    share_sum_[static_cast<std::size_t>(s)] += 1.0;
  }
}

void StripMasks::outlineByShares(const RobotGeometry& geometry) {
  const PixelGrid& grid = grid_;
  const std::size_t n_pixels = grid.pixelCount();
  const double half_width_m = geometry.strip_width_m / 2.0;
  // A pixel's points lie within half a diagonal of its centre.
  const double half_diagonal_m = grid.pixel_size_m * std::sqrt(0.5);
  const double reach_m = half_width_m + half_diagonal_m;

  // The centre lines' pieces, segment by segment (so that a strict "<" over them leaves exact
  // ties with the lower segment index), and for each pixel a centre line can reach the pieces
  // that can: candidates[slot[i]].
  struct Piece {
    Point a, b;
    std::int16_t segment;
  };
  std::vector<Piece> pieces;
  std::vector<std::int32_t> slot(n_pixels, -1);
  std::vector<std::vector<std::uint32_t>> candidates;
  for (std::size_t s = 0; s < geometry.segments.size(); ++s) {
    const auto& seg = geometry.segments[s];
    for (std::size_t k = 0; k + 1 < seg.centreline_Robot.size(); ++k) {
      const Point& a = seg.centreline_Robot[k];
      const Point& b = seg.centreline_Robot[k + 1];
      const auto piece = static_cast<std::uint32_t>(pieces.size());
      pieces.push_back({a, b, static_cast<std::int16_t>(s)});
      // The pixels whose square this piece's strip can meet: within its bounding box grown by
      // the reach, centres within the reach.
      const Box box = boxAround(grid, a, b, reach_m);
      for (int r = box.r0; r <= box.r1; ++r) {
        const double y = grid.yOfRow_m(r);
        for (int c = box.c0; c <= box.c1; ++c) {
          if (distanceToSegment_m(grid.xOfColumn_m(c), y, a, b) > reach_m) continue;
          const std::size_t i = static_cast<std::size_t>(r) * grid.width_px + c;
          if (slot[i] < 0) {
            slot[i] = static_cast<std::int32_t>(candidates.size());
            candidates.emplace_back();
          }
          candidates[static_cast<std::size_t>(slot[i])].push_back(piece);
        }
      }
    }
  }

  // The segment all of a pixel's points fall to, decided from the distances d_c of its centre
  // c to the pieces (a distance is 1-Lipschitz: a point p of the pixel lies within the half
  // diagonal h of c, so |d(p) - d_c| <= h): when the nearest piece n has d_c(n) + h <= half a
  // width and every piece q of another segment d_c(q) - h > d_c(n) + h, every point lies in the
  // strip and nearer to a piece of n's segment than to any other, which is what the points'
  // loop below finds point by point. -1 when the centre's distances do not decide it. A
  // margin of 1 nm on each bound covers the distances' rounding.
  constexpr double kMargin_m = 1e-9;
  std::vector<double> centre_m;
  const auto wholeSegment = [&](const std::vector<std::uint32_t>& mine, double x, double y) {
    centre_m.resize(mine.size());
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < mine.size(); ++k) {
      centre_m[k] = distanceToSegment_m(x, y, pieces[mine[k]].a, pieces[mine[k]].b);
      if (centre_m[k] < centre_m[nearest]) nearest = k;
    }
    const double farthest_m = centre_m[nearest] + half_diagonal_m + kMargin_m;
    if (!(farthest_m <= half_width_m)) return -1;
    const std::int16_t segment = pieces[mine[nearest]].segment;
    for (std::size_t k = 0; k < mine.size(); ++k) {
      if (pieces[mine[k]].segment != segment && !(centre_m[k] - half_diagonal_m - kMargin_m > farthest_m)) return -1;
    }
    return int(segment);
  };

  // Each candidate pixel's points, in raster order: the nearest piece within half a width.
  constexpr int kSub = kCoverageSubpixels;
  constexpr double kPointShare = 1.0 / (kSub * kSub);
  std::vector<int> points(geometry.segments.size(), 0);
  std::vector<std::int16_t> touched;
  for (std::size_t i = 0; i < n_pixels; ++i) {
    if (slot[i] < 0) continue;
    const auto& mine = candidates[static_cast<std::size_t>(slot[i])];
    const int row = static_cast<int>(i / static_cast<std::size_t>(grid.width_px));
    const int col = static_cast<int>(i % static_cast<std::size_t>(grid.width_px));
    touched.clear();
    const int whole = wholeSegment(mine, grid.xOfColumn_m(col), grid.yOfRow_m(row));
    if (whole >= 0) {
      // Every point of the pixel lies in this segment's strip, nearer to it than to any other.
      points[static_cast<std::size_t>(whole)] = kSub * kSub;
      touched.push_back(static_cast<std::int16_t>(whole));
    }
    for (int u = 0; whole < 0 && u < kSub; ++u) {
      const double y = grid.yOfRow_m(row - 0.5 + (u + 0.5) / kSub);
      for (int v = 0; v < kSub; ++v) {
        const double x = grid.xOfColumn_m(col - 0.5 + (v + 0.5) / kSub);
        double nearest_m = std::numeric_limits<double>::infinity();
        int segment = -1;
        for (const std::uint32_t p : mine) {
          const double d = distanceToSegment_m(x, y, pieces[p].a, pieces[p].b);
          if (d <= half_width_m && d < nearest_m) {
            nearest_m = d;
            segment = pieces[p].segment;
          }
        }
        if (segment < 0) continue;
        if (points[static_cast<std::size_t>(segment)]++ == 0) touched.push_back(static_cast<std::int16_t>(segment));
      }
    }
    if (touched.empty()) continue;
    std::sort(touched.begin(), touched.end());
    const auto k = static_cast<std::uint32_t>(sealing_pixels_.size());
    sealing_index_of_pixel_[i] = static_cast<std::int32_t>(k);
    sealing_pixels_.push_back(static_cast<std::uint32_t>(i));
    int most = 0;
    for (const std::int16_t s : touched) {
      const int count = points[static_cast<std::size_t>(s)];
      if (count > most) {  // ascending segments: a tie stays with the lower index
        most = count;
        segment_of_pixel_[i] = s;
      }
      leak_pixels_[static_cast<std::size_t>(s)].push_back(k);
      leak_shares_[static_cast<std::size_t>(s)].push_back(count * kPointShare);
      share_sum_[static_cast<std::size_t>(s)] += count * kPointShare;
      points[static_cast<std::size_t>(s)] = 0;
    }
    segment_pixels_[static_cast<std::size_t>(segment_of_pixel_[i])].push_back(k);
  }
}

}  // namespace climbsim::sealing
