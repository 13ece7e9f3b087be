// The rasteriser's index kept between runs (triangle_index_cache.hpp): read back, it is the
// built index byte for byte and renders the same images; it is found by its inputs alone, never
// trusted when cut short, and written only for large meshes into a directory that is set.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "analytic_scenes.hpp"
#include "render_scene.hpp"
#include "triangle_index_cache.hpp"

namespace climbsim::scene {
namespace {

namespace fs = std::filesystem;
using testing::pose;

/// A fresh directory under the test's temporary directory, removed at the end.
class CacheDir {
 public:
  CacheDir() : path_(fs::temp_directory_path() / ("climbsim-index-cache-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
  }
  ~CacheDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// A rough face with a crack and a step of about 115 000 triangles (above the copies' threshold).
TriangleMesh largeFace() {
  testing::AnalyticWall wall = testing::refined(testing::vGroove(), 0.0025, 0.3);
  const auto groove = wall.height_m;
  wall.height_m = [groove](double x, double y) {
    return groove(x, y) + 0.0011 * std::sin(230.0 * x + 0.7) * std::cos(170.0 * y) + (y > 0.05 ? 0.004 : 0.0);
  };
  TriangleMesh mesh = testing::meshWall(wall);
  // Two parts, so that the slots matter.
  for (std::size_t t = 0; t < mesh.part_ids.size(); ++t) mesh.part_ids[t] = t % 3 == 0 ? 1 : 0;
  return mesh;
}

std::vector<std::uint32_t> slotsOf(const TriangleMesh& mesh) { return mesh.part_ids; }

/// Every leaf, batch box and batch float of the index, and the leaves a few views visit.
std::vector<float> contentOf(const TriangleIndex& index) {
  std::vector<float> out;
  const auto put = [&](const Eigen::AlignedBox3f& box) {
    out.insert(out.end(), box.min().data(), box.min().data() + 3);
    out.insert(out.end(), box.max().data(), box.max().data() + 3);
  };
  for (const auto& leaf : index.leaves()) {
    put(leaf.box_F);
    out.push_back(float(leaf.slot)), out.push_back(float(leaf.first_batch)), out.push_back(float(leaf.batch_count));
    for (std::uint32_t b = leaf.first_batch; b < leaf.first_batch + leaf.batch_count; ++b) {
      put(index.batchBox_F(b));
      out.insert(out.end(), index.batchData_F(b), index.batchData_F(b) + TriangleIndex::kBatchFloats);
    }
  }
  for (double x : {-0.2, 0.0, 0.15}) {
    index.forEachLeafInView(Eigen::Matrix3d::Identity(), Eigen::Vector3d(x, 0.05, 0.0), 0.1, 0.08, -0.05, 0.05,
                            [&](const TriangleIndex::Leaf& leaf) { out.push_back(float(leaf.first_batch)); });
  }
  out.push_back(float(index.triangleCount()));
  return out;
}

bool sameBytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(TriangleIndexCache, TheCopyIsWrittenOnceAndReadBackAsTheBuiltIndexByteForByte) {
  const CacheDir dir;
  const TriangleMesh mesh = largeFace();
  ASSERT_GE(mesh.triangles.size(), kIndexCacheMinTriangles);
  const std::vector<float> built = contentOf(TriangleIndex(mesh, slotsOf(mesh)));
  const fs::path copy = dir.path() / triangleIndexCacheName(mesh, slotsOf(mesh));

  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), dir.path())), built));
  ASSERT_TRUE(fs::exists(copy));
  EXPECT_GT(fs::file_size(copy), mesh.triangles.size() * 36);  // every triangle's corners
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), dir.path())), built));

  // The second call read the copy: a float changed inside it comes back.
  {
    std::fstream f(copy, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(std::streamoff(fs::file_size(copy) / 2));
    const float changed = 123.0f;
    f.write(reinterpret_cast<const char*>(&changed), sizeof changed);
  }
  EXPECT_FALSE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), dir.path())), built));
}

TEST(TriangleIndexCache, ACopyIsFoundByTheMeshItIndexesSoAnyChangedVertexOrSlotBuildsAgain) {
  const CacheDir dir;
  const TriangleMesh mesh = largeFace();
  cachedTriangleIndex(mesh, slotsOf(mesh), dir.path());
  TriangleMesh moved = mesh;
  moved.vertices_m[moved.vertices_m.size() / 2].z() = std::nextafter(moved.vertices_m[moved.vertices_m.size() / 2].z(), 1.0f);
  std::vector<std::uint32_t> other_slots = slotsOf(mesh);
  other_slots[7] = 2;
  EXPECT_NE(triangleIndexCacheName(moved, slotsOf(moved)), triangleIndexCacheName(mesh, slotsOf(mesh)));
  EXPECT_NE(triangleIndexCacheName(mesh, other_slots), triangleIndexCacheName(mesh, slotsOf(mesh)));
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(moved, slotsOf(moved), dir.path())),
                        contentOf(TriangleIndex(moved, slotsOf(moved)))));
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, other_slots, dir.path())),
                        contentOf(TriangleIndex(mesh, other_slots))));
  std::size_t copies = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) copies += entry.path().extension() == ".index";
  EXPECT_EQ(copies, 3u);
}

TEST(TriangleIndexCache, ACopyCutShortOrNotOursIsPassedOverAndWrittenAgainWhole) {
  const CacheDir dir;
  const TriangleMesh mesh = largeFace();
  const std::vector<float> built = contentOf(TriangleIndex(mesh, slotsOf(mesh)));
  cachedTriangleIndex(mesh, slotsOf(mesh), dir.path());
  const fs::path copy = dir.path() / triangleIndexCacheName(mesh, slotsOf(mesh));
  const auto whole = fs::file_size(copy);
  fs::resize_file(copy, whole - 100);
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), dir.path())), built));
  EXPECT_EQ(fs::file_size(copy), whole);
  std::ofstream(copy, std::ios::binary | std::ios::trunc) << std::string(whole, 'x');
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), dir.path())), built));
  std::ifstream in(copy, std::ios::binary);
  char magic[16] = {};
  in.read(magic, sizeof magic);
  EXPECT_EQ(std::string(magic).rfind("climbsim-index", 0), 0u) << magic;  // ours again
}

TEST(TriangleIndexCache, SmallMeshesAndAnUnsetDirectoryWriteNothing) {
  const CacheDir dir;
  const TriangleMesh small = testing::meshWall(testing::refined(testing::step(), 0.01, 0.2));
  ASSERT_LT(small.triangles.size(), kIndexCacheMinTriangles);
  cachedTriangleIndex(small, slotsOf(small), dir.path());
  EXPECT_FALSE(fs::exists(dir.path()));
  const TriangleMesh mesh = largeFace();
  EXPECT_TRUE(sameBytes(contentOf(cachedTriangleIndex(mesh, slotsOf(mesh), std::nullopt)),
                        contentOf(TriangleIndex(mesh, slotsOf(mesh)))));
  EXPECT_FALSE(fs::exists(dir.path()));
}

TEST(TriangleIndexCache, ARendererWithTheCopyGivesTheSameDepthImagesBitForBit) {
  const CacheDir dir;
  const Pose T_W_F = pose(3.2, -1.7, 2.4, 90.0, 0.0, 0.0);
  TriangleMesh mesh;
  testing::appendMesh(mesh, largeFace(), T_W_F);
  RenderOptions cached;
  cached.index_cache_dir = dir.path();
  RenderScene writer(mesh, cached);  // writes the copy
  RenderScene reader(mesh, cached);  // reads it
  RenderScene fresh(mesh, RenderOptions{});
  DepthCameraParams camera;
  camera.samples_per_pixel = 16;
  camera.support_slope = 0.3;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 8; ++k) {
    const Pose T_W_C = T_W_F * pose(0.1 * unit(rng), 0.1 * unit(rng), 0.002 * unit(rng), 0, 0, 180.0 * unit(rng));
    const DepthImage a = fresh.renderDepth(T_W_C, camera);
    const DepthImage b = reader.renderDepth(T_W_C, camera);
    ASSERT_EQ(a.height_m.size(), b.height_m.size());
    EXPECT_EQ(std::memcmp(a.height_m.data(), b.height_m.data(), a.height_m.size() * sizeof(float)), 0) << k;
    EXPECT_EQ(a.support_px, b.support_px);
  }
  std::size_t copies = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) copies += entry.path().extension() == ".index";
  EXPECT_EQ(copies, 1u);
}

}  // namespace
}  // namespace climbsim::scene
