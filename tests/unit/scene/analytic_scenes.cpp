#include "analytic_scenes.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::scene::testing {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<double> withLines(std::vector<double> lines, double lo, double hi, int extra) {
  for (int k = 0; k <= extra; ++k) lines.push_back(lo + (hi - lo) * k / extra);
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

}  // namespace

DepthCameraParams sampledCamera(int side_px, double pixel_m, int samples, double support_slope) {
  DepthCameraParams camera;
  camera.width_px = camera.height_px = side_px;
  camera.pixel_size_m = pixel_m;
  camera.samples_per_pixel = samples;
  camera.support_slope = support_slope;
  return camera;
}

Pose pose(double x, double y, double z, double roll_deg, double pitch_deg, double yaw_deg) {
  Pose T = Pose::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch_deg * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_deg * kPi / 180.0, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

TriangleMesh meshWall(const AnalyticWall& wall, std::uint32_t part_id) {
  const auto& xs = wall.x_lines;
  const auto& ys = wall.y_lines;
  const int nx = static_cast<int>(xs.size()) - 1;
  const int ny = static_cast<int>(ys.size()) - 1;
  TriangleMesh mesh;
  // One vertex per (node, distinct height at the node); heights agreeing within 1e-9 m are
  // merged so that neighbouring cells share the vertex bit for bit.
  std::vector<std::vector<std::pair<double, std::uint32_t>>> node_vertices(static_cast<std::size_t>(nx + 1) * (ny + 1));
  auto vertexAt = [&](int i, int j, double h) {
    auto& list = node_vertices[static_cast<std::size_t>(j) * (nx + 1) + i];
    for (const auto& [hv, id] : list) {
      if (std::abs(hv - h) < 1e-9) return id;
    }
    const auto id = static_cast<std::uint32_t>(mesh.vertices_m.size());
    mesh.vertices_m.emplace_back(static_cast<float>(xs[i]), static_cast<float>(ys[j]), static_cast<float>(h));
    list.emplace_back(h, id);
    return id;
  };
  // corner[i][j][k]: vertex of corner k (0: (i,j), 1: (i+1,j), 2: (i+1,j+1), 3: (i,j+1)) of cell (i,j).
  std::vector<std::array<std::uint32_t, 4>> corner(static_cast<std::size_t>(nx) * ny);
  auto cellCorner = [&](int i, int j) -> std::array<std::uint32_t, 4>& { return corner[static_cast<std::size_t>(j) * nx + i]; };
  const int di[4] = {0, 1, 1, 0};
  const int dj[4] = {0, 0, 1, 1};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      // The cell's affine formula, sampled inside the cell and extrapolated to its corners.
      const double x0 = xs[i], x1 = xs[i + 1], y0 = ys[j], y1 = ys[j + 1];
      const double xa = x0 + 0.25 * (x1 - x0), xb = x0 + 0.75 * (x1 - x0);
      const double ya = y0 + 0.25 * (y1 - y0), yb = y0 + 0.75 * (y1 - y0);
      const double haa = wall.height_m(xa, ya), hba = wall.height_m(xb, ya), hab = wall.height_m(xa, yb);
      const double gx = (hba - haa) / (xb - xa), gy = (hab - haa) / (yb - ya);
      for (int k = 0; k < 4; ++k) {
        const double h = haa + gx * (xs[i + di[k]] - xa) + gy * (ys[j + dj[k]] - ya);
        cellCorner(i, j)[k] = vertexAt(i + di[k], j + dj[k], h);
      }
      const auto& c = cellCorner(i, j);
      mesh.triangles.push_back({c[0], c[1], c[2]});
      mesh.triangles.push_back({c[0], c[2], c[3]});
    }
  }
  auto wallQuad = [&](std::uint32_t a0, std::uint32_t a1, std::uint32_t b0, std::uint32_t b1) {
    if (a0 == b0 && a1 == b1) return;
    mesh.triangles.push_back({a0, a1, b1});
    mesh.triangles.push_back({a0, b1, b0});
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) wallQuad(cellCorner(i, j)[1], cellCorner(i, j)[2], cellCorner(i + 1, j)[0], cellCorner(i + 1, j)[3]);
      if (j + 1 < ny) wallQuad(cellCorner(i, j)[3], cellCorner(i, j)[2], cellCorner(i, j + 1)[0], cellCorner(i, j + 1)[1]);
    }
  }
  mesh.part_ids.assign(mesh.triangles.size(), part_id);
  return mesh;
}

void appendMesh(TriangleMesh& into, const TriangleMesh& mesh, const Pose& T) {
  const auto offset = static_cast<std::uint32_t>(into.vertices_m.size());
  for (const Eigen::Vector3f& v : mesh.vertices_m) into.vertices_m.push_back((T * v.cast<double>()).cast<float>());
  for (const auto& t : mesh.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  into.part_ids.insert(into.part_ids.end(), mesh.part_ids.begin(), mesh.part_ids.end());
}

TriangleMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::uint32_t part_id) {
  TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) {
    mesh.vertices_m.emplace_back(static_cast<float>(k & 1 ? hi.x() : lo.x()), static_cast<float>(k & 2 ? hi.y() : lo.y()),
                                 static_cast<float>(k & 4 ? hi.z() : lo.z()));
  }
  const std::uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  mesh.part_ids.assign(mesh.triangles.size(), part_id);
  return mesh;
}

double expectedDepth(const AnalyticWall& wall, const Pose& T_F_C, const DepthCameraParams& camera, int row, int col) {
  const Eigen::Vector3d o = T_F_C * Eigen::Vector3d(camera.pixelCentreX_m(col), camera.pixelCentreY_m(row), camera.near_m);
  const Eigen::Vector3d d = -T_F_C.linear().col(2);
  const double t_end = camera.near_m - camera.far_m;
  // Parameters where the ray crosses a grid line: between two of them the surface is affine
  // along the ray, so the height gap g(t) = z(t) - h(x(t), y(t)) is affine there.
  std::vector<double> ts = {0.0, t_end};
  // Only the lines between the ray's ends matter (the lines are sorted).
  auto addCrossings = [&](const std::vector<double>& lines, double from, double delta) {
    if (delta == 0.0) return;
    const double lo = std::min(from, from + t_end * delta), hi = std::max(from, from + t_end * delta);
    for (auto it = std::lower_bound(lines.begin(), lines.end(), lo); it != lines.end() && *it <= hi; ++it) {
      ts.push_back((*it - from) / delta);
    }
  };
  addCrossings(wall.x_lines, o.x(), d.x());
  addCrossings(wall.y_lines, o.y(), d.y());
  std::sort(ts.begin(), ts.end());
  auto inside = [&](const Eigen::Vector3d& p) {
    return p.x() > wall.x_lines.front() && p.x() < wall.x_lines.back() && p.y() > wall.y_lines.front() &&
           p.y() < wall.y_lines.back();
  };
  auto depthAt = [&](double t) { return std::max(camera.near_m - t, camera.far_m); };
  // The surface is crossed inside an interval where g changes sign (top face), or at a grid
  // line where z lies between the heights on either side (vertical face). A ray that starts
  // inside the solid (the wall reaches above near) sees only such crossings, like the meshes.
  bool have_previous = false;
  double h_previous_end = 0.0;
  for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
    const double ta = std::max(ts[k], 0.0), tb = std::min(ts[k + 1], t_end);
    if (tb <= ta) continue;
    const double t1 = ta + 0.25 * (tb - ta), t2 = ta + 0.75 * (tb - ta);
    const Eigen::Vector3d p1 = o + t1 * d, p2 = o + t2 * d;
    if (!inside(p1)) {
      have_previous = false;
      continue;
    }
    const double h1 = wall.height_m(p1.x(), p1.y()), h2 = wall.height_m(p2.x(), p2.y());
    const double h_slope = (h2 - h1) / (t2 - t1);
    const double ha = h1 + h_slope * (ta - t1), hb = h1 + h_slope * (tb - t1);
    const double za = o.z() + ta * d.z(), zb = o.z() + tb * d.z();
    if (have_previous && za <= std::max(ha, h_previous_end) && za >= std::min(ha, h_previous_end) &&
        ha != h_previous_end) {
      return depthAt(ta);
    }
    const double ga = za - ha, gb = zb - hb;
    if ((ga > 0.0 && gb <= 0.0) || (ga < 0.0 && gb >= 0.0)) return depthAt(ta + ga / (ga - gb) * (tb - ta));
    have_previous = true;
    h_previous_end = hb;
  }
  return camera.far_m;
}

AnalyticWall refined(AnalyticWall wall, double spacing_m, double half_m) {
  const int extra = static_cast<int>(std::lround(2.0 * half_m / spacing_m));
  auto keep = [&](std::vector<double> lines) {
    std::vector<double> inner;
    for (const double l : lines) {
      if (l > -half_m && l < half_m) inner.push_back(l);
    }
    return withLines(inner, -half_m, half_m, extra);
  };
  wall.x_lines = keep(wall.x_lines);
  wall.y_lines = keep(wall.y_lines);
  return wall;
}

AnalyticWall tiltedPlane() {
  AnalyticWall w;
  w.height_m = [](double x, double y) { return 0.004 + 0.03 * x - 0.02 * y; };
  w.x_lines = withLines({}, -1.0, 1.0, 8);
  w.y_lines = withLines({}, -1.0, 1.0, 8);
  return w;
}

AnalyticWall step() {
  AnalyticWall w;
  constexpr double kEdge = 0.0731;
  w.height_m = [](double x, double) { return x < kEdge ? 0.011 : -0.0123; };
  w.x_lines = withLines({kEdge}, -1.0, 1.0, 8);
  w.y_lines = withLines({}, -1.0, 1.0, 8);
  return w;
}

AnalyticWall rectangularHole() {
  AnalyticWall w;
  w.height_m = [](double x, double y) {
    if (x > -0.1013 && x < 0.1307 && y > -0.0709 && y < 0.0517) return -0.0271;  // within range
    if (x > 0.2011 && x < 0.2833 && y > 0.1021 && y < 0.2113) return -0.2;       // below far
    return 0.0007;
  };
  w.x_lines = withLines({-0.1013, 0.1307, 0.2011, 0.2833}, -1.0, 1.0, 8);
  w.y_lines = withLines({-0.0709, 0.0517, 0.1021, 0.2113}, -1.0, 1.0, 8);
  return w;
}

AnalyticWall vGroove() {
  AnalyticWall w;
  constexpr double kAxis = 0.0467, kHalfWidth = 0.0313, kDepth = 0.0189;
  w.height_m = [](double x, double) { return -kDepth * std::max(0.0, 1.0 - std::abs(x - kAxis) / kHalfWidth); };
  w.x_lines = withLines({kAxis - kHalfWidth, kAxis, kAxis + kHalfWidth}, -1.0, 1.0, 8);
  w.y_lines = withLines({}, -1.0, 1.0, 8);
  return w;
}

}  // namespace climbsim::scene::testing
