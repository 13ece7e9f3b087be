#include "climbsim/robot/chamber_polygons.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>

namespace climbsim::robot {

namespace {

/// Corners closer than this are the same corner [m] (far below a depth pixel).
constexpr double kSameCornerM = 1e-7;

using Key = std::pair<std::int64_t, std::int64_t>;

Key keyOf(Point p) {
  return {std::llround(p.x_m / kSameCornerM), std::llround(p.y_m / kSameCornerM)};
}

double cross(Point o, Point a, Point b) { return (a.x_m - o.x_m) * (b.y_m - o.y_m) - (a.y_m - o.y_m) * (b.x_m - o.x_m); }

double distance(Point a, Point b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

double distanceToSegment(Point a, Point b, Point p) {
  const double dx = b.x_m - a.x_m;
  const double dy = b.y_m - a.y_m;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(a.x_m + t * dx - p.x_m, a.y_m + t * dy - p.y_m);
}

/// True if the open segments ab and cd cross at a single interior point of both.
bool properlyCross(Point a, Point b, Point c, Point d) {
  const double d1 = cross(a, b, c);
  const double d2 = cross(a, b, d);
  const double d3 = cross(c, d, a);
  const double d4 = cross(c, d, b);
  const double eps = 1e-18;
  return ((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps)) && ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps));
}

/// True if ab and cd lie on one line and overlap over a positive length.
bool collinearOverlap(Point a, Point b, Point c, Point d) {
  const double len = distance(a, b);
  if (len <= 0.0) return false;
  if (std::abs(cross(a, b, c)) / len > kSameCornerM || std::abs(cross(a, b, d)) / len > kSameCornerM) return false;
  const auto along = [&](Point p) { return ((p.x_m - a.x_m) * (b.x_m - a.x_m) + (p.y_m - a.y_m) * (b.y_m - a.y_m)) / len; };
  const double lo = std::max(0.0, std::min(along(c), along(d)));
  const double hi = std::min(len, std::max(along(c), along(d)));
  return hi - lo > kSameCornerM;
}

double polylineLength(const std::vector<Point>& line) {
  double sum_m = 0.0;
  for (std::size_t k = 1; k < line.size(); ++k) sum_m += distance(line[k - 1], line[k]);
  return sum_m;
}

std::string pieceName(const std::string& base, std::size_t piece) {
  if (piece == 0) return base;
  return base + static_cast<char>('a' + static_cast<int>(std::min<std::size_t>(piece, 25)));
}

/// Runs of consecutive edges (cyclic) of one chamber whose owner (-1: outside, else the
/// neighbour's index) satisfies `keep`, as polylines along the chamber's outline.
template <class Keep>
std::vector<std::vector<Point>> runs(const Polygon& outline, const std::vector<int>& owner, Keep keep) {
  const std::size_t n = outline.size();
  std::vector<std::vector<Point>> out;
  // Start after an edge that is not kept, so that no run wraps around the start.
  std::size_t start = 0;
  bool all = true;
  for (std::size_t k = 0; k < n; ++k) {
    if (!keep(owner[k])) {
      start = (k + 1) % n;
      all = false;
      break;
    }
  }
  if (all) {
    std::vector<Point> closed(outline);
    closed.push_back(outline.front());
    out.push_back(std::move(closed));
    return out;
  }
  std::vector<Point> current;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (start + i) % n;
    if (keep(owner[k])) {
      if (current.empty()) current.push_back(outline[k]);
      current.push_back(outline[(k + 1) % n]);
    } else if (!current.empty()) {
      out.push_back(std::move(current));
      current.clear();
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

}  // namespace

double signedArea(const Polygon& polygon) {
  double sum = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Point& a = polygon[k];
    const Point& b = polygon[(k + 1) % polygon.size()];
    sum += a.x_m * b.y_m - b.x_m * a.y_m;
  }
  return sum / 2.0;
}

Point centroid(const Polygon& polygon) {
  double cx = 0.0;
  double cy = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Point& a = polygon[k];
    const Point& b = polygon[(k + 1) % polygon.size()];
    const double w = a.x_m * b.y_m - b.x_m * a.y_m;
    cx += (a.x_m + b.x_m) * w;
    cy += (a.y_m + b.y_m) * w;
  }
  const double area = signedArea(polygon);
  return Point{cx / (6.0 * area), cy / (6.0 * area)};
}

Polygon counterClockwise(Polygon polygon) {
  if (signedArea(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

bool strictlyInside(const Polygon& polygon, Point p, double margin_m) {
  bool inside = false;
  for (std::size_t k = 0, j = polygon.size() - 1; k < polygon.size(); j = k++) {
    const Point& a = polygon[k];
    const Point& b = polygon[j];
    if (distanceToSegment(a, b, p) <= margin_m) return false;
    if ((a.y_m > p.y_m) != (b.y_m > p.y_m) && p.x_m < (b.x_m - a.x_m) * (p.y_m - a.y_m) / (b.y_m - a.y_m) + a.x_m) {
      inside = !inside;
    }
  }
  return inside;
}

double distanceToPolyline(const std::vector<Point>& line, Point p) {
  double best = distance(line.front(), p);
  for (std::size_t k = 1; k < line.size(); ++k) best = std::min(best, distanceToSegment(line[k - 1], line[k], p));
  return best;
}

bool selfIntersects(const Polygon& polygon) {
  const std::size_t n = polygon.size();
  std::set<Key> corners;
  for (const Point& p : polygon) {
    if (!corners.insert(keyOf(p)).second) return true;  // a corner visited twice
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const Point a = polygon[i], b = polygon[(i + 1) % n], c = polygon[j], d = polygon[(j + 1) % n];
      if (properlyCross(a, b, c, d) || collinearOverlap(a, b, c, d)) return true;
    }
  }
  return false;
}

bool overlap(const Polygon& a, const Polygon& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (properlyCross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    }
  }
  const auto anyInside = [](const Polygon& p, const Polygon& q) {
    for (const Point& corner : p) {
      if (strictlyInside(q, corner, kSameCornerM)) return true;
    }
    return strictlyInside(q, centroid(p), kSameCornerM);
  };
  return anyInside(a, b) || anyInside(b, a);
}

SegmentsOrProblems sealingSegments(const std::vector<Polygon>& outlines) {
  using Kind = RobotGeometry::SegmentKind;
  SegmentsOrProblems out;
  // Directed edges by their corners: an edge b->a of chamber j matches a->b of chamber i.
  std::map<std::pair<Key, Key>, int> edge_owner;
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    const Polygon& o = outlines[c];
    for (std::size_t k = 0; k < o.size(); ++k) edge_owner[{keyOf(o[k]), keyOf(o[(k + 1) % o.size()])}] = static_cast<int>(c);
  }
  std::vector<std::vector<int>> owner(outlines.size());  // per chamber and edge: neighbour or -1
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    const Polygon& o = outlines[c];
    for (std::size_t k = 0; k < o.size(); ++k) {
      const auto it = edge_owner.find({keyOf(o[(k + 1) % o.size()]), keyOf(o[k])});
      owner[c].push_back(it == edge_owner.end() ? -1 : it->second);
    }
  }
  // An outer edge lying along another chamber's edge: the two do not share corners.
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    const Polygon& o = outlines[c];
    for (std::size_t k = 0; k < o.size(); ++k) {
      if (owner[c][k] != -1) continue;
      for (std::size_t d = 0; d < outlines.size(); ++d) {
        if (d == c) continue;
        const Polygon& q = outlines[d];
        for (std::size_t m = 0; m < q.size(); ++m) {
          if (collinearOverlap(o[k], o[(k + 1) % o.size()], q[m], q[(m + 1) % q.size()])) {
            out.problems.push_back("chamber " + std::to_string(c + 1) + " edge " + std::to_string(k + 1) +
                                   " runs along chamber " + std::to_string(d + 1) +
                                   "'s edge without the same corners: give both the same corner points");
            d = outlines.size();
            break;
          }
        }
      }
    }
  }
  // The outer edges must chain into exactly one closed loop.
  std::map<Key, std::vector<Key>> next;
  std::size_t outer_edges = 0;
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    const Polygon& o = outlines[c];
    for (std::size_t k = 0; k < o.size(); ++k) {
      if (owner[c][k] != -1) continue;
      next[keyOf(o[k])].push_back(keyOf(o[(k + 1) % o.size()]));
      ++outer_edges;
    }
  }
  std::size_t loops = 0;
  bool branched = false;
  std::set<Key> visited;
  for (const auto& [start, targets] : next) {
    if (targets.size() != 1) branched = true;
    if (visited.count(start) != 0) continue;
    ++loops;
    Key at = start;
    while (visited.insert(at).second) {
      const auto it = next.find(at);
      if (it == next.end()) break;
      at = it->second.front();
    }
  }
  if (outer_edges == 0 || branched || loops != 1) {
    out.problems.push_back("the outer sealing strip does not close into one loop (" + std::to_string(loops) +
                           " loops): the chambers must form one piece without holes");
  }
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    const auto pieces = runs(outlines[c], owner[c], [](int o) { return o == -1; });
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      out.segments.push_back({pieceName("outer" + std::to_string(c + 1), p), Kind::kOuter, static_cast<VolumeId>(c),
                              kAmbient, polylineLength(pieces[p]), pieces[p]});
    }
  }
  for (std::size_t c = 0; c < outlines.size(); ++c) {
    std::set<int> neighbours(owner[c].begin(), owner[c].end());
    for (const int n : neighbours) {
      if (n <= static_cast<int>(c)) continue;
      const auto pieces = runs(outlines[c], owner[c], [n](int o) { return o == n; });
      for (std::size_t p = 0; p < pieces.size(); ++p) {
        out.segments.push_back({pieceName("wall" + std::to_string(c + 1) + "_" + std::to_string(n + 1), p), Kind::kWall,
                                static_cast<VolumeId>(c), static_cast<VolumeId>(n), polylineLength(pieces[p]),
                                pieces[p]});
      }
    }
  }
  return out;
}

}  // namespace climbsim::robot
