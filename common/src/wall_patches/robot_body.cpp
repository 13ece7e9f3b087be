#include "climbsim/wall_patches/robot_body.hpp"

#include <cmath>

namespace climbsim::surface {
namespace {

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

}  // namespace

SurfaceMesh robotBodyMesh() {
  SurfaceMesh mesh;
  addCylinder(mesh, {0.0f, 0.0f, 0.115f}, Eigen::Vector3f::UnitZ(), 0.40f, 0.17f, 48);
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * M_PI * k / 3.0;
    const Eigen::Vector3f radial(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
    addCylinder(mesh, 0.26f * radial + Eigen::Vector3f(0.0f, 0.0f, 0.05f), radial, 0.05f, 0.04f, 24);
  }
  return mesh;
}

}  // namespace climbsim::surface
