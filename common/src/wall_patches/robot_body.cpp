#include "climbsim/wall_patches/robot_body.hpp"

#include <cmath>
#include <numeric>

namespace climbsim::surface {
namespace {

using Point = RobotGeometry::Point;

/// Twice the signed area of triangle a b c (> 0 counter-clockwise).
double cross(const Point& a, const Point& b, const Point& c) {
  return (b.x_m - a.x_m) * (c.y_m - a.y_m) - (b.y_m - a.y_m) * (c.x_m - a.x_m);
}

/// Whether p lies inside or on triangle a b c (counter-clockwise).
bool inside(const Point& p, const Point& a, const Point& b, const Point& c) {
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

/// Closed cylinder about `axis` (unit) through `centre`, outward normals.
void addCylinder(SurfaceMesh& mesh, const Eigen::Vector3f& centre, const Eigen::Vector3f& axis, float radius_m,
                 float length_m, int sides) {
  const Eigen::Vector3f u = axis.unitOrthogonal(), w = axis.cross(u);
  const auto base = static_cast<std::uint32_t>(mesh.vertices_m.size());
  const Eigen::Vector3f half = 0.5f * length_m * axis;
  mesh.vertices_m.push_back(centre - half);
  mesh.vertices_m.push_back(centre + half);
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * M_PI * k / sides;
    const Eigen::Vector3f r = radius_m * (static_cast<float>(std::cos(a)) * u + static_cast<float>(std::sin(a)) * w);
    mesh.vertices_m.push_back(centre - half + r);
    mesh.vertices_m.push_back(centre + half + r);
  }
  const std::uint32_t bottom = base, top = base + 1;
  for (int k = 0; k < sides; ++k) {
    const std::uint32_t b0 = base + 2 + 2 * k, t0 = b0 + 1;
    const std::uint32_t b1 = base + 2 + 2 * ((k + 1) % sides), t1 = b1 + 1;
    // u, w, axis is right-handed, so k -> k+1 turns counter-clockwise about the axis.
    mesh.triangles.push_back({b0, b1, t1});
    mesh.triangles.push_back({b0, t1, t0});
    mesh.triangles.push_back({top, t0, t1});
    mesh.triangles.push_back({bottom, b1, b0});
  }
}

/// The outline extruded from z0 to z1: bottom face (facing -z), top face (+z), side walls.
void addPrism(SurfaceMesh& mesh, const std::vector<Point>& outline, float z0, float z1) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices_m.size());
  const auto n = static_cast<std::uint32_t>(outline.size());
  for (const float z : {z0, z1}) {
    for (const Point& p : outline) mesh.vertices_m.emplace_back(static_cast<float>(p.x_m), static_cast<float>(p.y_m), z);
  }
  for (const auto& t : triangulatePolygon(outline)) {
    mesh.triangles.push_back({base + t[0], base + t[2], base + t[1]});          // bottom, seen from -z
    mesh.triangles.push_back({base + n + t[0], base + n + t[1], base + n + t[2]});  // top
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t b0 = base + k, b1 = base + (k + 1) % n;
    mesh.triangles.push_back({b0, b1, b1 + n});
    mesh.triangles.push_back({b0, b1 + n, b0 + n});
  }
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> triangulatePolygon(const std::vector<Point>& outline) {
  std::vector<std::uint32_t> left(outline.size());
  std::iota(left.begin(), left.end(), 0u);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  while (left.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < left.size() && !clipped; ++i) {
      const std::uint32_t a = left[(i + left.size() - 1) % left.size()], b = left[i], c = left[(i + 1) % left.size()];
      if (cross(outline[a], outline[b], outline[c]) <= 0.0) continue;  // reflex or flat corner
      bool ear = true;
      for (const std::uint32_t p : left) {
        if (p != a && p != b && p != c && inside(outline[p], outline[a], outline[b], outline[c])) ear = false;
      }
      if (!ear) continue;
      triangles.push_back({a, b, c});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) {
      // Only flat corners are left (collinear points): a fan closes the rest.
      for (std::size_t i = 1; i + 1 < left.size(); ++i) triangles.push_back({left[0], left[i], left[i + 1]});
      return triangles;
    }
  }
  if (left.size() == 3) triangles.push_back({left[0], left[1], left[2]});
  return triangles;
}

SurfaceMesh robotBodyMesh(const RobotGeometry& geometry) {
  SurfaceMesh mesh;
  addPrism(mesh, geometry.body_outline_Robot, kBodyBottomM, kBodyTopM);
  for (const auto& wheel : geometry.wheels) {
    const auto r = static_cast<float>(wheel.radius_m);
    const Eigen::Vector3f centre(static_cast<float>(wheel.p_RobotWheel.x_m), static_cast<float>(wheel.p_RobotWheel.y_m), r);
    switch (wheel.kind) {
      case RobotDescription::WheelKind::kSteerable: {
        const Eigen::Vector3f radial(static_cast<float>(std::cos(wheel.angle_rad)),
                                     static_cast<float>(std::sin(wheel.angle_rad)), 0.0f);
        addCylinder(mesh, centre, radial, r, kSteerableTyreM, kWheelSides);
        break;
      }
      case RobotDescription::WheelKind::kFixed:
        addCylinder(mesh, centre, Eigen::Vector3f::UnitY(), r, kFixedTyreM, kWheelSides);
        break;
      case RobotDescription::WheelKind::kCaster:
        addCylinder(mesh, centre, Eigen::Vector3f::UnitY(), r, kCasterTyreM, kWheelSides);
        break;
    }
  }
  return mesh;
}

}  // namespace climbsim::surface
