// The copies of assimp's reads (climbsim/wall/mesh_cache.hpp): the same triangles bit for bit,
// found by the file's bytes alone, never trusted when cut short, and kept under their limit.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>

#include "climbsim/wall/mesh_cache.hpp"
#include "climbsim/wall/mesh_file.hpp"
#include "scene_test_files.hpp"

namespace climbsim::scene {
namespace {

namespace fs = std::filesystem;

/// Sets (or with nullopt unsets) an environment variable for its life and restores what was there.
class EnvSetting {
 public:
  EnvSetting(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    set(value);
  }
  ~EnvSetting() { set(old_); }

 private:
  void set(const std::optional<std::string>& value) {
    if (value) {
      ::setenv(name_, value->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  const char* name_;
  std::optional<std::string> old_;
};

/// CLIMBSIM_MESH_CACHE for the test's life.
class CacheSetting : public EnvSetting {
 public:
  explicit CacheSetting(const std::optional<std::string>& value) : EnvSetting("CLIMBSIM_MESH_CACHE", value) {}
};

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void expectIdentical(const LocalMesh& a, const LocalMesh& b, const std::string& what) {
  ASSERT_EQ(a.vertices_m.size(), b.vertices_m.size()) << what;
  ASSERT_EQ(a.triangles.size(), b.triangles.size()) << what;
  for (std::size_t i = 0; i < a.vertices_m.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.vertices_m[i][k], b.vertices_m[i][k]) << what << ": vertex " << i;
  }
  for (std::size_t i = 0; i < a.triangles.size(); ++i) EXPECT_EQ(a.triangles[i], b.triangles[i]) << what << ": triangle " << i;
}

TEST(MeshCache, AReadFromTheCopyGivesAssimpsVerticesAndTrianglesBitForBit) {
  testing::TempDir dir;
  const std::string ply = dir.write("wall.ply", testing::asPly(testing::tetrahedron()));
  const std::string stl = dir.write("wall.stl", testing::asStl(testing::tetrahedron()));
  for (const auto& path : {ply, stl}) {
    LocalMesh assimp;
    {
      CacheSetting off("off");
      assimp = loadMeshFile(path, "test", "file");
    }
    CacheSetting on(dir / "cache");
    const LocalMesh first = loadMeshFile(path, "test", "file");  // assimp, and writes the copy
    ASSERT_TRUE(fs::exists(dir.path() / "cache" / meshCacheName(bytesOf(path)))) << path;
    const LocalMesh second = loadMeshFile(path, "test", "file");  // the copy
    expectIdentical(assimp, first, path + ", the read that wrote the copy");
    expectIdentical(assimp, second, path + ", the read from the copy");
    EXPECT_EQ(second.file, path);
  }
}

TEST(MeshCache, TheCopyIsFoundByTheFilesBytesSoAnEditedFileIsReadAgain) {
  testing::TempDir dir;
  CacheSetting on(dir / "cache");
  const std::string path = dir.write("wall.ply", testing::asPly(testing::tetrahedron()));
  // A copy under this file's bytes is what a read returns: here a square, to tell it apart.
  LocalMesh square;
  square.vertices_m = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  writeMeshCache(dir.path() / "cache", bytesOf(path), square);
  EXPECT_EQ(loadMeshFile(path, "test", "file").triangles.size(), 2u) << "the copy was not used";
  // The same name, other bytes (one vertex moved, the file's size unchanged): assimp again.
  testing::TestMesh moved = testing::tetrahedron();
  moved.vertices[1].x() = 1.6;
  dir.write("wall.ply", testing::asPly(moved));
  const LocalMesh edited = loadMeshFile(path, "test", "file");
  ASSERT_EQ(edited.triangles.size(), 4u);
  bool found = false;
  for (const auto& v : edited.vertices_m) found = found || v.x() == 1.6f;
  EXPECT_TRUE(found) << "the edited vertex is not in the read";
}

TEST(MeshCache, ACopyCutShortOrNotOursIsPassedOverAndWrittenAgain) {
  testing::TempDir dir;
  CacheSetting on(dir / "cache");
  const std::string path = dir.write("wall.ply", testing::asPly(testing::tetrahedron()));
  const LocalMesh whole = loadMeshFile(path, "test", "file");
  const fs::path copy = dir.path() / "cache" / meshCacheName(bytesOf(path));
  const auto size = fs::file_size(copy);
  fs::resize_file(copy, size - 5);
  EXPECT_FALSE(readMeshCache(dir.path() / "cache", bytesOf(path))) << "a copy cut short was read";
  expectIdentical(whole, loadMeshFile(path, "test", "file"), "after the copy was cut short");
  EXPECT_EQ(fs::file_size(copy), size) << "the copy was not written again";
  std::ofstream(copy, std::ios::binary | std::ios::trunc) << std::string(size, 'x');
  EXPECT_FALSE(readMeshCache(dir.path() / "cache", bytesOf(path))) << "a foreign file was read";
  expectIdentical(whole, loadMeshFile(path, "test", "file"), "after the copy was overwritten");
}

TEST(MeshCache, OnlySelfContainedFormatsAreCopiedAndAnUnwritableCacheOnlyCostsTheRead) {
  testing::TempDir dir;
  {
    CacheSetting on(dir / "cache");
    loadMeshFile(dir.write("wall.obj", testing::asObj(testing::tetrahedron())), "test", "file");
    EXPECT_FALSE(fs::exists(dir.path() / "cache")) << "an OBJ file may name further files: no copy";
  }
  const std::string blocker = dir.write("a-file", "not a directory");
  CacheSetting unwritable(blocker + "/cache");
  const std::string path = dir.write("wall.ply", testing::asPly(testing::tetrahedron()));
  EXPECT_EQ(loadMeshFile(path, "test", "file").triangles.size(), 4u);
}

TEST(MeshCache, TheLeastRecentlyUsedCopiesGoWhenTheCopiesExceedTheirLimit) {
  testing::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  LocalMesh mesh;
  mesh.vertices_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  writeMeshCache(cache, "bytes a", mesh);
  writeMeshCache(cache, "bytes b", mesh);
  const auto one = fs::file_size(cache / meshCacheName("bytes a"));
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(cache / meshCacheName("bytes a"), now - std::chrono::hours(2));
  fs::last_write_time(cache / meshCacheName("bytes b"), now - std::chrono::hours(1));
  ASSERT_TRUE(readMeshCache(cache, "bytes a"));  // a is now the most recently used
  writeMeshCache(cache, "bytes c", mesh, 2 * one);
  EXPECT_TRUE(fs::exists(cache / meshCacheName("bytes a")));
  EXPECT_FALSE(fs::exists(cache / meshCacheName("bytes b"))) << "the least recently used copy stayed";
  EXPECT_TRUE(fs::exists(cache / meshCacheName("bytes c")));
}

TEST(MeshCache, TheDirectoryFollowsTheSettingThenXdgThenHome) {
  {
    CacheSetting set("/some/where");
    EXPECT_EQ(meshCacheDir(), fs::path("/some/where"));
  }
  {
    CacheSetting off("off");
    EXPECT_FALSE(meshCacheDir());
  }
  CacheSetting unset(std::nullopt);
  {
    EnvSetting xdg("XDG_CACHE_HOME", "/xdg");
    EXPECT_EQ(meshCacheDir(), fs::path("/xdg/climbsim/meshes"));
  }
  EnvSetting no_xdg("XDG_CACHE_HOME", std::nullopt);
  {
    EnvSetting home("HOME", "/home/engineer");
    EXPECT_EQ(meshCacheDir(), fs::path("/home/engineer/.cache/climbsim/meshes"));
  }
  EnvSetting no_home("HOME", std::nullopt);
  EXPECT_FALSE(meshCacheDir()) << "no home, no setting: no copies";
}

}  // namespace
}  // namespace climbsim::scene
