#include "climbsim/wall_patches/wall_patch.hpp"

#include <algorithm>
#include <cmath>

#include "climbsim/wall_patches/face_mesh.hpp"
#include "climbsim/wall_patches/rough_surface.hpp"
#include "climbsim/wall_patches/seeded_random.hpp"
#include "climbsim/wall_patches/surface_features.hpp"

namespace climbsim::surface {
namespace {

constexpr std::uint64_t kRoughStream = 1;
constexpr std::uint64_t kNetworkStream = 2;

/// Adds the strip between the rim vertices `rim` (sorted along the side) and their
/// projections onto z = bottom, oriented so that the normal points along `outward`.
void addSideStrip(SurfaceMesh& mesh, const std::vector<std::uint32_t>& rim, float bottom_z,
                  const Eigen::Vector3f& outward) {
  std::vector<std::uint32_t> foot;
  for (std::uint32_t v : rim) {
    Eigen::Vector3f p = mesh.vertices_m[v];
    p.z() = bottom_z;
    mesh.vertices_m.push_back(p);
    foot.push_back(static_cast<std::uint32_t>(mesh.vertices_m.size() - 1));
  }
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Eigen::Vector3f n =
        (mesh.vertices_m[b] - mesh.vertices_m[a]).cross(mesh.vertices_m[c] - mesh.vertices_m[a]);
    if (n.dot(outward) >= 0.0f)
      mesh.triangles.push_back({a, b, c});
    else
      mesh.triangles.push_back({a, c, b});
  };
  for (std::size_t k = 0; k + 1 < rim.size(); ++k) {
    add(rim[k], rim[k + 1], foot[k]);
    add(rim[k + 1], foot[k + 1], foot[k]);
  }
}

}  // namespace

std::uint64_t crackNetworkSeed(std::uint64_t spec_seed) { return deriveSeed(spec_seed, kNetworkStream); }

WallPatch generateWallPatch(const PatchSpec& spec) {
  WallPatch patch;
  patch.grid_cells = std::max(1, static_cast<int>(std::lround(spec.size_m / spec.grid_m)));
  patch.grid_spacing_m = spec.size_m / patch.grid_cells;

  const HeightGrid rough =
      roughHeights(spec.rough, spec.size_m, patch.grid_cells, deriveSeed(spec.seed, kRoughStream));
  const SurfaceFeatures features(spec, crackNetworkSeed(spec.seed), patch.grid_spacing_m);
  FaceMesh face(rough);
  for (const CutSegment& cut : features.cuts()) face.cut(cut);

  SurfaceMesh& mesh = patch.mesh;
  const auto& xy = face.xy();
  mesh.vertices_m.reserve(xy.size() + 8 * static_cast<std::size_t>(patch.grid_cells) + 16);
  for (std::size_t v = 0; v < xy.size(); ++v) {
    const double z = face.baseZ()[v] + features.heightOffset(xy[v]);
    mesh.vertices_m.emplace_back(static_cast<float>(xy[v].x()), static_cast<float>(xy[v].y()),
                                 static_cast<float>(z));
  }
  mesh.triangles = face.triangles();
  patch.face_triangles = mesh.triangles.size();

  // The rim of each side, sorted along it (border vertices hold exactly 0 or size).
  const double size = face.size();
  std::vector<std::uint32_t> rims[4];  // x = 0, x = size, y = 0, y = size
  for (std::uint32_t v = 0; v < xy.size(); ++v) {
    if (xy[v].x() == 0.0) rims[0].push_back(v);
    if (xy[v].x() == size) rims[1].push_back(v);
    if (xy[v].y() == 0.0) rims[2].push_back(v);
    if (xy[v].y() == size) rims[3].push_back(v);
  }
  for (int side = 0; side < 4; ++side) {
    const int along = side < 2 ? 1 : 0;
    std::sort(rims[side].begin(), rims[side].end(),
              [&](std::uint32_t a, std::uint32_t b) { return xy[a][along] < xy[b][along]; });
  }
  const auto bottom = static_cast<float>(-size);
  addSideStrip(mesh, rims[0], bottom, -Eigen::Vector3f::UnitX());
  addSideStrip(mesh, rims[1], bottom, Eigen::Vector3f::UnitX());
  addSideStrip(mesh, rims[2], bottom, -Eigen::Vector3f::UnitY());
  addSideStrip(mesh, rims[3], bottom, Eigen::Vector3f::UnitY());

  const auto s = static_cast<float>(size);
  const auto base = static_cast<std::uint32_t>(mesh.vertices_m.size());
  mesh.vertices_m.emplace_back(0.0f, 0.0f, bottom);
  mesh.vertices_m.emplace_back(s, 0.0f, bottom);
  mesh.vertices_m.emplace_back(s, s, bottom);
  mesh.vertices_m.emplace_back(0.0f, s, bottom);
  // Seen from -z (outside the back), counter-clockwise.
  mesh.triangles.push_back({base, base + 2, base + 1});
  mesh.triangles.push_back({base, base + 3, base + 2});
  return patch;
}

}  // namespace climbsim::surface
