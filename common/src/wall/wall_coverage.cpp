#include "climbsim/wall/wall_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace climbsim::scene {

WallCoverage::WallCoverage(const TriangleMesh& mesh_W, double reach_m, double cell_m)
    : reach_m_(reach_m), cell_m_(cell_m) {
  if (!(reach_m >= 0.0) || !(cell_m > 0.0)) throw std::invalid_argument("WallCoverage: reach >= 0 and cell > 0");
  // The box of the triangles that can cover anything (some corner at or above -reach).
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  auto reachable = [&](const std::array<std::uint32_t, 3>& t) {
    return std::max({mesh_W.vertices_m[t[0]].z(), mesh_W.vertices_m[t[1]].z(), mesh_W.vertices_m[t[2]].z()}) >=
           -reach_m;
  };
  for (const auto& t : mesh_W.triangles) {
    if (!reachable(t)) continue;
    for (const auto i : t) {
      lo_x = std::min(lo_x, double(mesh_W.vertices_m[i].x()));
      hi_x = std::max(hi_x, double(mesh_W.vertices_m[i].x()));
      lo_y = std::min(lo_y, double(mesh_W.vertices_m[i].y()));
      hi_y = std::max(hi_y, double(mesh_W.vertices_m[i].y()));
    }
  }
  if (!(lo_x <= hi_x) || !(lo_y <= hi_y) || !std::isfinite(hi_x - lo_x) || !std::isfinite(hi_y - lo_y)) return;
  while ((std::ceil((hi_x - lo_x) / cell_m_) + 1) * (std::ceil((hi_y - lo_y) / cell_m_) + 1) > double(kMaxCells)) {
    cell_m_ *= 2.0;
  }
  x0_ = lo_x;
  y0_ = lo_y;
  nx_ = static_cast<std::size_t>(std::ceil((hi_x - lo_x) / cell_m_)) + 1;
  ny_ = static_cast<std::size_t>(std::ceil((hi_y - lo_y) / cell_m_)) + 1;
  covered_.assign(nx_ * ny_, 0);
  for (const auto& t : mesh_W.triangles) {
    if (!reachable(t)) continue;
    const Eigen::Vector3d a = mesh_W.vertices_m[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh_W.vertices_m[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh_W.vertices_m[t[2]].cast<double>();
    // Barycentric coordinates in the wall plane; a triangle standing on edge covers nothing.
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-18) continue;
    // Cells whose centre x0 + (i + 0.5) cell may lie in the triangle's box.
    const auto first = [&](double lo, double origin) {
      return static_cast<std::ptrdiff_t>(std::ceil((lo - origin) / cell_m_ - 0.5));
    };
    const auto last = [&](double hi, double origin) {
      return static_cast<std::ptrdiff_t>(std::floor((hi - origin) / cell_m_ - 0.5));
    };
    const std::ptrdiff_t i0 = std::max<std::ptrdiff_t>(0, first(std::min({a.x(), b.x(), c.x()}), x0_));
    const std::ptrdiff_t i1 = std::min<std::ptrdiff_t>(nx_ - 1, last(std::max({a.x(), b.x(), c.x()}), x0_));
    const std::ptrdiff_t j0 = std::max<std::ptrdiff_t>(0, first(std::min({a.y(), b.y(), c.y()}), y0_));
    const std::ptrdiff_t j1 = std::min<std::ptrdiff_t>(ny_ - 1, last(std::max({a.y(), b.y(), c.y()}), y0_));
    for (std::ptrdiff_t j = j0; j <= j1; ++j) {
      const double y = y0_ + (double(j) + 0.5) * cell_m_;
      for (std::ptrdiff_t i = i0; i <= i1; ++i) {
        std::uint8_t& cell = covered_[std::size_t(j) * nx_ + std::size_t(i)];
        if (cell) continue;
        const double x = x0_ + (double(i) + 0.5) * cell_m_;
        const double u = ((x - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (y - a.y())) / det;
        const double v = ((b.x() - a.x()) * (y - a.y()) - (x - a.x()) * (b.y() - a.y())) / det;
        const double eps = 1e-9;
        if (u < -eps || v < -eps || u + v > 1.0 + eps) continue;
        const double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
        if (z >= -reach_m_) cell = 1;
      }
    }
  }
  bool any = false;
  for (std::size_t j = 0; j < ny_; ++j) {
    for (std::size_t i = 0; i < nx_; ++i) {
      if (!covered_[j * nx_ + i]) continue;
      const double x = x0_ + double(i) * cell_m_, y = y0_ + double(j) * cell_m_;
      if (!any) {
        min_x_ = x, max_x_ = x + cell_m_, min_y_ = y, max_y_ = y + cell_m_;
        any = true;
      }
      min_x_ = std::min(min_x_, x), max_x_ = std::max(max_x_, x + cell_m_);
      min_y_ = std::min(min_y_, y), max_y_ = std::max(max_y_, y + cell_m_);
    }
  }
  if (!any) nx_ = ny_ = 0, covered_.clear();
}

bool WallCoverage::covered(double x_m, double y_m) const {
  if (empty() || !std::isfinite(x_m) || !std::isfinite(y_m)) return false;
  const double fi = std::floor((x_m - x0_) / cell_m_), fj = std::floor((y_m - y0_) / cell_m_);
  if (fi < 0.0 || fj < 0.0 || fi >= double(nx_) || fj >= double(ny_)) return false;
  return covered_[std::size_t(fj) * nx_ + std::size_t(fi)] != 0;
}

std::size_t wallPartOf(const Scene& scene, const std::string& pose_element) {
  return static_cast<std::size_t>(scene.parts()[scene.poseElement(pose_element).part].parent);
}

WallCoverage wallCoverage(const Scene& scene, const std::string& pose_element, double reach_m, double cell_m) {
  const Pose T_W_world = scene.worldPose(wallPartOf(scene, pose_element)).inverse();
  TriangleMesh mesh_W = scene.staticMesh();
  const Eigen::Isometry3f T = T_W_world.cast<float>();
  for (auto& v : mesh_W.vertices_m) v = T * v;
  return WallCoverage(mesh_W, reach_m, cell_m);
}

double coverageReach(const SceneDescription& description, const std::string& camera) {
  for (const auto& c : description.cameras) {
    if (c.name == camera && c.far_limit_m > 0.0) return c.far_limit_m;
  }
  return 0.05;
}

}  // namespace climbsim::scene
