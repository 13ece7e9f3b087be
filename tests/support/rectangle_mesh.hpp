#pragma once
// Walls made of axis-aligned rectangles, for the tests of what lies under a point of the wall.

#include <cstdint>
#include <utility>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// A rectangle [x0, x1] x [y0, y1] at height z [m] as two triangles, appended to `mesh`.
inline void addRectangle(TriangleMesh& mesh, double x0, double x1, double y0, double y1, double z) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices_m.size());
  for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}) {
    mesh.vertices_m.emplace_back(float(x), float(y), float(z));
  }
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  mesh.part_ids.insert(mesh.part_ids.end(), 2, 0);
}

}  // namespace climbsim::scene
