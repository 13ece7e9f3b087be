#pragma once
/// @file
/// The structured face as a planar triangulation (x, y in the patch frame) that carries the
/// rough height of every vertex, and into which straight vertex lines are cut so that the
/// breakpoints of crack, groove, hole and step profiles become mesh edges.

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "climbsim/wall_patches/rough_surface.hpp"

namespace climbsim::surface {

/// A straight cut: the points origin + t dir, t in [t_begin, t_end] (dir has unit length;
/// +-infinity for a whole line).
struct CutSegment {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d dir = Eigen::Vector2d::UnitX();
  double t_begin = 0.0;
  double t_end = 0.0;
};

/// Conforming triangulation of the square [0, size]^2, counter-clockwise seen from +z.
class FaceMesh {
 public:
  /// Two triangles per grid cell; base heights from `rough`.
  explicit FaceMesh(const HeightGrid& rough);

  /// Splits every triangle whose chord with the cut's line overlaps [t_begin, t_end] along
  /// that chord (new vertices on the crossed edges, base height linearly interpolated so the
  /// rough surface keeps its shape); a neighbour that shares one cut edge but lies beyond the
  /// segment's end is split from that vertex to its opposite corner, so the mesh stays
  /// conforming. Vertices within 0.1 um of the line count as on it.
  void cut(const CutSegment& segment);

  const std::vector<Eigen::Vector2d>& xy() const { return xy_m_; }
  const std::vector<double>& baseZ() const { return base_z_m_; }
  const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return triangles_; }
  double size() const { return size_m_; }

 private:
  /// Signed distance of vertex v from the current cut's line [m], 0 within kOnLineM.
  double side(std::uint32_t v) const;
  std::uint32_t edgeVertex(std::uint32_t a, std::uint32_t b);
  void addToBins(std::uint32_t triangle);
  void replace(std::uint32_t triangle, const std::vector<std::array<std::uint32_t, 3>>& pieces);

  double size_m_ = 0.0;
  double spacing_m_ = 0.0;
  std::vector<Eigen::Vector2d> xy_m_;
  std::vector<double> base_z_m_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;

  // Spatial bins (a superset of the triangles overlapping each bin) to find the triangles
  // near a cut without visiting the whole face.
  double bin_m_ = 0.0;
  int bins_per_side_ = 0;
  std::vector<std::vector<std::uint32_t>> bins_;
  std::vector<std::uint32_t> visit_stamp_;
  std::uint32_t pass_ = 0;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_vertices_;
  Eigen::Vector2d cut_origin_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d cut_normal_ = Eigen::Vector2d::UnitY();
};

}  // namespace climbsim::surface
