#include "climbsim/wall_patches/face_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace climbsim::surface {
namespace {

constexpr double kOnLineM = 1e-7;
constexpr int kCellsPerBin = 8;

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

double distanceToSegment(const Eigen::Vector2d& p, const CutSegment& s) {
  const double t = std::clamp(s.dir.dot(p - s.origin), s.t_begin, s.t_end);
  return (p - (s.origin + t * s.dir)).norm();
}

}  // namespace

FaceMesh::FaceMesh(const HeightGrid& rough) {
  const int n = rough.cells;
  spacing_m_ = rough.spacing_m;
  size_m_ = n * spacing_m_;
  xy_m_.reserve(static_cast<std::size_t>(n + 1) * (n + 1));
  // x = size i / n (not i spacing) so that the border vertices sit exactly on 0 and size.
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      xy_m_.emplace_back(size_m_ * i / n, size_m_ * j / n);
      base_z_m_.push_back(rough.at(i, j));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto v00 = static_cast<std::uint32_t>(j * (n + 1) + i);
      const std::uint32_t v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
      triangles_.push_back({v00, v10, v11});
      triangles_.push_back({v00, v11, v01});
    }
  bins_per_side_ = (n + kCellsPerBin - 1) / kCellsPerBin;
  bin_m_ = kCellsPerBin * spacing_m_;
  bins_.assign(static_cast<std::size_t>(bins_per_side_) * bins_per_side_, {});
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) addToBins(t);
}

void FaceMesh::addToBins(std::uint32_t triangle) {
  Eigen::Vector2d lo = xy_m_[triangles_[triangle][0]], hi = lo;
  for (int k = 1; k < 3; ++k) {
    lo = lo.cwiseMin(xy_m_[triangles_[triangle][k]]);
    hi = hi.cwiseMax(xy_m_[triangles_[triangle][k]]);
  }
  // Shrunk by a hair so that a triangle touching a bin border is not listed in both bins.
  const auto bin = [&](double v) {
    return std::clamp(static_cast<int>(std::floor(v / bin_m_)), 0, bins_per_side_ - 1);
  };
  const double hair = 1e-9;
  for (int by = bin(lo.y() + hair); by <= bin(hi.y() - hair); ++by)
    for (int bx = bin(lo.x() + hair); bx <= bin(hi.x() - hair); ++bx)
      bins_[static_cast<std::size_t>(by) * bins_per_side_ + bx].push_back(triangle);
}

double FaceMesh::side(std::uint32_t v) const {
  const double s = cut_normal_.dot(xy_m_[v] - cut_origin_);
  return std::abs(s) < kOnLineM ? 0.0 : s;
}

std::uint32_t FaceMesh::edgeVertex(std::uint32_t a, std::uint32_t b) {
  const std::uint64_t key = edgeKey(a, b);
  const auto found = edge_vertices_.find(key);
  if (found != edge_vertices_.end()) return found->second;
  // From the lower index, so the point does not depend on which triangle asked first.
  if (a > b) std::swap(a, b);
  const double sa = side(a), sb = side(b);
  const double f = sa / (sa - sb);
  xy_m_.push_back(xy_m_[a] + f * (xy_m_[b] - xy_m_[a]));
  base_z_m_.push_back(base_z_m_[a] + f * (base_z_m_[b] - base_z_m_[a]));
  const auto v = static_cast<std::uint32_t>(xy_m_.size() - 1);
  // An edge on the face border keeps its constant coordinate exactly (the side faces find
  // their rim by it).
  for (int axis = 0; axis < 2; ++axis)
    if (xy_m_[a][axis] == xy_m_[b][axis]) xy_m_[v][axis] = xy_m_[a][axis];
  edge_vertices_.emplace(key, v);
  return v;
}

void FaceMesh::cut(const CutSegment& segment) {
  cut_origin_ = segment.origin;
  cut_normal_ = Eigen::Vector2d(-segment.dir.y(), segment.dir.x());
  edge_vertices_.clear();
  ++pass_;
  visit_stamp_.resize(triangles_.size(), 0);

  // Candidates: triangles in bins near the segment. A neighbour of a split triangle lies
  // within two grid cells of the line, hence the reach.
  const double reach = 0.7072 * bin_m_ + 3.0 * spacing_m_;
  const double big = 4.0 * size_m_;
  const double t0 = std::max(segment.t_begin, -big), t1 = std::min(segment.t_end, big);
  const CutSegment clipped{segment.origin, segment.dir, t0, t1};
  const Eigen::Vector2d a = segment.origin + t0 * segment.dir, b = segment.origin + t1 * segment.dir;
  const auto bin = [&](double v) {
    return std::clamp(static_cast<int>(std::floor(v / bin_m_)), 0, bins_per_side_ - 1);
  };
  std::vector<std::uint32_t> candidates;
  for (int by = bin(std::min(a.y(), b.y()) - reach); by <= bin(std::max(a.y(), b.y()) + reach); ++by)
    for (int bx = bin(std::min(a.x(), b.x()) - reach); bx <= bin(std::max(a.x(), b.x()) + reach); ++bx) {
      const Eigen::Vector2d centre((bx + 0.5) * bin_m_, (by + 0.5) * bin_m_);
      if (distanceToSegment(centre, clipped) > reach) continue;
      for (std::uint32_t t : bins_[static_cast<std::size_t>(by) * bins_per_side_ + bx])
        if (visit_stamp_[t] != pass_) {
          visit_stamp_[t] = pass_;
          candidates.push_back(t);
        }
    }

  // Pass 1: which triangles the segment crosses; their crossed edges get a vertex.
  std::vector<char> crossed(candidates.size(), 0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const auto& tri = triangles_[candidates[c]];
    const double s[3] = {side(tri[0]), side(tri[1]), side(tri[2])};
    const bool positive = s[0] > 0 || s[1] > 0 || s[2] > 0;
    const bool negative = s[0] < 0 || s[1] < 0 || s[2] < 0;
    if (!positive || !negative) continue;
    double chord_lo = std::numeric_limits<double>::infinity(), chord_hi = -chord_lo;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      Eigen::Vector2d point;
      if (s[k] == 0.0) {
        point = xy_m_[tri[k]];
      } else if (s[k] * s[l] < 0.0) {
        point = xy_m_[tri[k]] + s[k] / (s[k] - s[l]) * (xy_m_[tri[l]] - xy_m_[tri[k]]);
      } else {
        continue;
      }
      const double t = segment.dir.dot(point - segment.origin);
      chord_lo = std::min(chord_lo, t);
      chord_hi = std::max(chord_hi, t);
    }
    if (chord_hi < segment.t_begin || chord_lo > segment.t_end) continue;
    crossed[c] = 1;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      if (s[k] * s[l] < 0.0) edgeVertex(tri[k], tri[l]);
    }
  }
  if (edge_vertices_.empty()) return;

  // Pass 2: split along the points on the line (cut points and corners on the line).
  struct Entry {
    std::uint32_t vertex;
    bool on_line;
  };
  std::vector<std::array<std::uint32_t, 3>> pieces;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::uint32_t t = candidates[c];
    const std::array<std::uint32_t, 3> tri = triangles_[t];
    std::vector<Entry> loop;
    std::uint32_t cut_point[3];
    int cut_edges = 0;
    for (int k = 0; k < 3; ++k) {
      loop.push_back({tri[k], crossed[c] && side(tri[k]) == 0.0});
      const auto found = edge_vertices_.find(edgeKey(tri[k], tri[(k + 1) % 3]));
      cut_point[k] = found == edge_vertices_.end() ? UINT32_MAX : found->second;
      if (found != edge_vertices_.end()) {
        loop.push_back({found->second, true});
        ++cut_edges;
      }
    }
    if (cut_edges == 0) continue;
    pieces.clear();
    if (cut_edges == 3) {
      const std::uint32_t m01 = cut_point[0], m12 = cut_point[1], m20 = cut_point[2];
      pieces = {{tri[0], m01, m20}, {m01, tri[1], m12}, {m20, m12, tri[2]}, {m01, m12, m20}};
      replace(t, pieces);
      continue;
    }
    if (!crossed[c] && cut_edges == 1) {
      // The segment ends here: split from the cut point to the opposite corner.
      for (int k = 0; k < 3; ++k)
        if (cut_point[k] != UINT32_MAX)
          for (Entry& e : loop)
            if (e.vertex == tri[(k + 2) % 3]) e.on_line = true;
    }
    std::vector<std::size_t> on;
    for (std::size_t k = 0; k < loop.size(); ++k)
      if (loop[k].on_line) on.push_back(k);
    if (on.size() != 2) continue;  // cannot happen for a straight line through a triangle
    const auto fan = [&](std::size_t from, std::size_t to) {
      std::vector<std::uint32_t> poly;
      for (std::size_t k = from;; k = (k + 1) % loop.size()) {
        poly.push_back(loop[k].vertex);
        if (k == to) break;
      }
      if (poly.size() == 3) {
        pieces.push_back({poly[0], poly[1], poly[2]});
      } else if (poly.size() == 4) {
        // The shorter diagonal gives the better-shaped pair.
        const double d02 = (xy_m_[poly[0]] - xy_m_[poly[2]]).squaredNorm();
        const double d13 = (xy_m_[poly[1]] - xy_m_[poly[3]]).squaredNorm();
        if (d02 <= d13) {
          pieces.push_back({poly[0], poly[1], poly[2]});
          pieces.push_back({poly[0], poly[2], poly[3]});
        } else {
          pieces.push_back({poly[1], poly[2], poly[3]});
          pieces.push_back({poly[1], poly[3], poly[0]});
        }
      } else {
        for (std::size_t k = 1; k + 1 < poly.size(); ++k) pieces.push_back({poly[0], poly[k], poly[k + 1]});
      }
    };
    fan(on[0], on[1]);
    fan(on[1], on[0]);
    replace(t, pieces);
  }
}

void FaceMesh::replace(std::uint32_t triangle, const std::vector<std::array<std::uint32_t, 3>>& pieces) {
  triangles_[triangle] = pieces.front();
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    triangles_.push_back(pieces[k]);
    addToBins(static_cast<std::uint32_t>(triangles_.size() - 1));
  }
}

}  // namespace climbsim::surface
