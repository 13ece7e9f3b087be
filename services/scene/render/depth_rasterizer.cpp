#include "depth_rasterizer.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::scene {

namespace {

bool lexLess(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

// Edge function of p against the directed edge a -> b: (b - a) x (p - a) in the u-v plane.
// Evaluated from the lexicographically smaller vertex so that both triangles sharing the edge
// get the same value (up to sign) for the same pixel centre.
struct Edge {
  double du, dv, au, av, sign;
  Edge(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const bool swap = lexLess(b, a);
    const Eigen::Vector3d& s = swap ? b : a;
    const Eigen::Vector3d& e = swap ? a : b;
    du = e.x() - s.x();
    dv = e.y() - s.y();
    au = s.x();
    av = s.y();
    sign = swap ? -1.0 : 1.0;
  }
  double at(double u, double v) const { return sign * (du * (v - av) - dv * (u - au)); }
};

}  // namespace

void rasterizeDepth(const TriangleIndex& index, const Pose& T_CF, const DepthCameraParams& camera,
                    const std::vector<char>& slot_excluded, std::vector<float>& z_buffer, RasterScratch& scratch) {
  const int W = camera.width_px;
  const int H = camera.height_px;
  const double s = camera.pixel_size_m;
  const double near = camera.near_m;
  const double far = camera.far_m;

  // p_F -> (u, v, z): u = x_C / s + W/2 - 0.5 (column of a centre), v = -y_C / s + H/2 - 0.5.
  Eigen::Matrix3d A = T_CF.linear();
  Eigen::Vector3d a = T_CF.translation();
  A.row(0) /= s;
  a.x() = a.x() / s + 0.5 * W - 0.5;
  A.row(1) /= -s;
  a.y() = -a.y() / s + 0.5 * H - 0.5;

  const Eigen::Matrix3d& R_CF = T_CF.linear();
  const Eigen::Vector3d& t_CF = T_CF.translation();
  const std::vector<Eigen::Vector3f>& verts = index.leafVertices_F();
  const auto& tris = index.leafTriangles();

  index.forEachLeafInView(R_CF, t_CF, 0.5 * W * s, 0.5 * H * s, far, near, [&](const TriangleIndex::Leaf& leaf) {
    if (!slot_excluded.empty() && slot_excluded[leaf.slot]) return;
    scratch.uvz.resize(leaf.vertex_count);
    for (std::uint32_t k = 0; k < leaf.vertex_count; ++k) {
      scratch.uvz[k] = A * verts[leaf.first_vertex + k].cast<double>() + a;
    }
    for (std::uint32_t t = leaf.first_triangle; t < leaf.first_triangle + leaf.triangle_count; ++t) {
      const Eigen::Vector3d& p0 = scratch.uvz[tris[t][0]];
      const Eigen::Vector3d& p1 = scratch.uvz[tris[t][1]];
      const Eigen::Vector3d& p2 = scratch.uvz[tris[t][2]];
      const double z_lo = std::min({p0.z(), p1.z(), p2.z()});
      const double z_hi = std::max({p0.z(), p1.z(), p2.z()});
      if (z_lo > near || z_hi < far) continue;
      const int c0 = std::max(0, static_cast<int>(std::ceil(std::min({p0.x(), p1.x(), p2.x()}))));
      const int c1 = std::min(W - 1, static_cast<int>(std::floor(std::max({p0.x(), p1.x(), p2.x()}))));
      if (c0 > c1) continue;
      const int r0 = std::max(0, static_cast<int>(std::ceil(std::min({p0.y(), p1.y(), p2.y()}))));
      const int r1 = std::min(H - 1, static_cast<int>(std::floor(std::max({p0.y(), p1.y(), p2.y()}))));
      if (r0 > r1) continue;
      // Weights of p0, p1, p2 are the edge functions of the opposite edges.
      const Edge e0(p1, p2), e1(p2, p0), e2(p0, p1);
      const double area = e2.at(p2.x(), p2.y());
      if (area == 0.0) continue;  // seen edge-on: the neighbouring faces cover its pixels
      const double orient = area > 0.0 ? 1.0 : -1.0;
      for (int r = r0; r <= r1; ++r) {
        float* row = z_buffer.data() + static_cast<std::size_t>(r) * W;
        for (int c = c0; c <= c1; ++c) {
          const double w0 = orient * e0.at(c, r);
          const double w1 = orient * e1.at(c, r);
          const double w2 = orient * e2.at(c, r);
          if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
          const double w = w0 + w1 + w2;
          if (w <= 0.0) continue;
          // Convex weights keep z within the triangle's range even when it is nearly edge-on.
          const double z = std::clamp((w0 * p0.z() + w1 * p1.z() + w2 * p2.z()) / w, z_lo, z_hi);
          if (z <= near && static_cast<float>(z) > row[c]) row[c] = static_cast<float>(z);
        }
      }
    }
  });
}

}  // namespace climbsim::scene
