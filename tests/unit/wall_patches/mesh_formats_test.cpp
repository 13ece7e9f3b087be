// Every output format round-trips through assimp with the same triangles.

#include <gtest/gtest.h>

#include <algorithm>

#include "climbsim/errors.hpp"
#include "climbsim/wall_patches/mesh_io.hpp"
#include "surface_sampler.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace climbsim::surface {
namespace {

class SurfaceMeshFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(SurfaceMeshFormat, RoundTripsWithTheSameTrianglesAndExtent) {
  PatchSpec spec;
  spec.size_m = 0.2;
  spec.grid_m = 0.01;
  spec.seed = 3;
  spec.cracks.push_back(LinearFeature{0.1, 0.1, 20.0, 0.004, 0.01, 0.0, Profile::kV});
  const WallPatch patch = generateWallPatch(spec);
  const test::ScopedTempDir dir(std::string("format_") + GetParam());
  const std::string path = dir.path + "/patch." + GetParam();
  writeMeshChecked(path, patch.mesh);
  const SurfaceMesh back = readMesh(path);
  ASSERT_EQ(back.triangles.size(), patch.mesh.triangles.size());

  // Same extent and same deepest point (the crack floor), in the same frame.
  const auto extent = [](const SurfaceMesh& m) {
    Eigen::Vector3f lo = m.vertices_m.front(), hi = lo;
    for (const auto& v : m.vertices_m) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    return std::pair{lo, hi};
  };
  const auto [lo, hi] = extent(patch.mesh);
  const auto [back_lo, back_hi] = extent(back);
  EXPECT_LT((lo - back_lo).norm(), 1e-6f);
  EXPECT_LT((hi - back_hi).norm(), 1e-6f);
  // The face's lowest point is on the crack floor: 10 mm below the rough surface.
  float face_min = 1.0f;
  for (std::size_t t = 0; t < patch.face_triangles; ++t)
    for (auto v : patch.mesh.triangles[t]) face_min = std::min(face_min, patch.mesh.vertices_m[v].z());
  float back_face_min = 1.0f;
  for (const auto& v : back.vertices_m)
    if (v.z() > -0.1f) back_face_min = std::min(back_face_min, v.z());
  EXPECT_NEAR(back_face_min, face_min, 1e-6f);
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceMeshFormat, ::testing::Values("ply", "obj", "stl", "gltf", "glb", "dae"));

TEST(SurfaceMeshFormat, UnknownExtensionIsAConfigError) {
  EXPECT_THROW(exportFormatFor("patch.xyz"), ConfigError);
  EXPECT_THROW(exportFormatFor("patch"), ConfigError);
  EXPECT_EQ(exportFormatFor("A.PLY"), "plyb");
}

TEST(SurfaceMeshFormat, UnreadableFileIsAConfigError) {
  const test::ScopedTempDir dir_scope("unreadable");
  const std::string& dir = dir_scope.path;
  EXPECT_THROW(readMesh(dir + "/missing.ply"), ConfigError);
}

}  // namespace
}  // namespace climbsim::surface
