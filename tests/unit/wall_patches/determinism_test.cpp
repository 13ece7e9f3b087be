// The generator is a function of its spec and seed: the same seed writes the same bytes,
// another seed writes another surface.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include <tinyxml2.h>

#include "climbsim/wall_patches/mesh_io.hpp"
#include "climbsim/wall_patches/pylon_scene.hpp"
#include "surface_sampler.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace climbsim::surface {
namespace {

PatchSpec everythingSpec(std::uint64_t seed) {
  PatchSpec spec;
  spec.size_m = 0.6;
  spec.grid_m = 0.005;
  spec.seed = seed;
  spec.cracks.push_back(LinearFeature{0.3, 0.2, 10.0, 0.006, 0.02, 0.0, Profile::kRect});
  spec.grooves.push_back(LinearFeature{0.2, 0.3, 80.0, 0.02, 0.01, 0.3, Profile::kU});
  spec.network.count = 3;
  spec.holes.push_back(Hole{0.45, 0.45, 0.04, 0.02});
  spec.steps.push_back(Step{0.3, 0.5, -5.0, 0.008});
  return spec;
}

TEST(SurfaceDeterminism, SameSeedGivesIdenticalBytes) {
  const test::ScopedTempDir dir_scope("determinism");
  const std::string& dir = dir_scope.path;
  writeMesh(dir + "/a.ply", generateWallPatch(everythingSpec(17)).mesh);
  writeMesh(dir + "/b.ply", generateWallPatch(everythingSpec(17)).mesh);
  const std::string a = test::readBytes(dir + "/a.ply"), b = test::readBytes(dir + "/b.ply");
  ASSERT_GT(a.size(), 10000u);
  EXPECT_TRUE(a == b);
}

TEST(SurfaceDeterminism, AnotherSeedGivesAnotherSurfaceAndNetwork) {
  const test::ScopedTempDir dir_scope("seeds");
  const std::string& dir = dir_scope.path;
  writeMesh(dir + "/a.ply", generateWallPatch(everythingSpec(17)).mesh);
  writeMesh(dir + "/b.ply", generateWallPatch(everythingSpec(18)).mesh);
  EXPECT_FALSE(test::readBytes(dir + "/a.ply") == test::readBytes(dir + "/b.ply"));
  const SurfaceMesh a = readMesh(dir + "/a.ply"), b = readMesh(dir + "/b.ply");
  const test::SurfaceSampler sa(a), sb(b);
  // Away from features the rough heights of two seeds are uncorrelated.
  int differ = 0;
  for (double x = 0.05; x < 0.3; x += 0.02)
    if (std::abs(*sa.height(x, 0.05) - *sb.height(x, 0.05)) > 1e-5) ++differ;
  EXPECT_GE(differ, 10);
}

TEST(SurfaceDefaultPylon, IsDeterministicAndComplete) {
  const test::ScopedTempDir a_scope("pylon_a"), b_scope("pylon_b");
  const std::string &a = a_scope.path, &b = b_scope.path;
  const auto written_a = writePylonScene(a, 1);
  const auto written_b = writePylonScene(b, 1);
  ASSERT_EQ(written_a.size(), written_b.size());
  std::size_t triangles = 0;
  for (std::size_t k = 0; k < written_a.size(); ++k) {
    const std::string name = std::filesystem::path(written_a[k].path).filename().string();
    EXPECT_TRUE(test::readBytes(written_a[k].path) == test::readBytes(b + "/meshes/" + name)) << name;
    triangles += written_a[k].triangles;
  }
  EXPECT_LT(triangles, 2500000u);
  EXPECT_TRUE(test::readBytes(a + "/pylon.xml") == test::readBytes(b + "/pylon.xml"));
  EXPECT_TRUE(test::readBytes(a + "/walls/pylon_blocks.xml") == test::readBytes(b + "/walls/pylon_blocks.xml"));

  // The scene names the frames the other services rely on; every file it names exists.
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile((a + "/pylon.xml").c_str()), tinyxml2::XML_SUCCESS);
  std::map<std::string, std::string> files, parents;
  for (auto* part = doc.RootElement()->FirstChildElement("part"); part; part = part->NextSiblingElement("part")) {
    files[part->Attribute("name")] = part->Attribute("file");
    parents[part->Attribute("name")] = part->Attribute("attached_to");
  }
  EXPECT_EQ(files["WALL"], "");
  EXPECT_EQ(parents["WALL"], "ROOT");
  EXPECT_EQ(parents["ROBOT"], "WALL");
  EXPECT_EQ(parents["DEPTH_CAMERA"], "ROBOT");
  EXPECT_EQ(files["DEPTH_CAMERA"], "");
  EXPECT_EQ(parents["TCP"], "ROBOT");
  EXPECT_EQ(files["PYLON"], "walls/pylon_blocks.xml");
  EXPECT_TRUE(std::filesystem::exists(a + "/" + files["ROBOT"]));
  tinyxml2::XMLDocument blocks;
  ASSERT_EQ(blocks.LoadFile((a + "/walls/pylon_blocks.xml").c_str()), tinyxml2::XML_SUCCESS);
  int block_count = 0;
  for (auto* part = blocks.RootElement()->FirstChildElement("part"); part; part = part->NextSiblingElement("part")) {
    EXPECT_TRUE(std::filesystem::exists(a + "/walls/" + part->Attribute("file"))) << part->Attribute("file");
    ++block_count;
  }
  EXPECT_EQ(block_count, 12);

  // The crack-descent crack: at W y = 0.70 across the middle column, 10 mm wide, 40 mm deep.
  const SurfaceMesh crack_block = readMesh(a + "/meshes/block_c1_r0_crack.ply");
  const test::SurfaceSampler sampler(crack_block);
  for (double x : {0.3, 1.0, 1.7}) {
    const double floor = *sampler.height(x, 0.70);
    const double beside = 0.5 * (*sampler.height(x, 0.70 - 0.0051) + *sampler.height(x, 0.70 + 0.0051));
    EXPECT_NEAR(beside - floor, 0.040, 0.004) << "x " << x;  // rough: +-1 mm RMS on either side
    EXPECT_LT(*sampler.height(x, 0.70 - 0.0047), beside - 0.035);  // inside: on the floor
  }
}

}  // namespace
}  // namespace climbsim::surface
