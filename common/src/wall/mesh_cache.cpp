#include "climbsim/wall/mesh_cache.hpp"

#include <assimp/version.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <string_view>
#include <system_error>
#include <vector>

#include "climbsim/cache_files.hpp"

namespace climbsim::scene {
namespace fs = std::filesystem;
namespace {

/// The copy's layout: this header, then the vertices as 3 floats each and the triangles as 3
/// uint32 each, in the machine's byte order (a copy is only read where it was written).
struct Header {
  char magic[16];                   ///< kMagic, with the layout's version
  std::uint32_t assimp_version[2];  ///< major * 1000 + minor, and revision, of the assimp that read it
  std::uint64_t file_size;          ///< bytes of the mesh file
  std::uint64_t file_hash;          ///< std::hash of the mesh file's bytes
  std::uint64_t vertex_count;       ///< vertices that follow the header
  std::uint64_t triangle_count;     ///< triangles that follow the vertices
};
constexpr char kMagic[16] = "climbsim-mesh-1";

/// The mesh file's identity: its size and the hash of its bytes (hashed once per read).
struct FileKey {
  std::uint64_t size;
  std::uint64_t hash;
  explicit FileKey(const std::string& bytes)
      : size(bytes.size()), hash(std::hash<std::string_view>{}(bytes)) {}
};

std::string nameFor(const FileKey& key) {
  char name[64];
  std::snprintf(name, sizeof(name), "%016llx-%llu.mesh", static_cast<unsigned long long>(key.hash),
                static_cast<unsigned long long>(key.size));
  return name;
}

Header headerFor(const FileKey& key, std::uint64_t vertices, std::uint64_t triangles) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  h.assimp_version[0] = aiGetVersionMajor() * 1000 + aiGetVersionMinor();
  h.assimp_version[1] = aiGetVersionRevision();
  h.file_size = key.size;
  h.file_hash = key.hash;
  h.vertex_count = vertices;
  h.triangle_count = triangles;
  return h;
}

std::uintmax_t payloadBytes(std::uint64_t vertices, std::uint64_t triangles) {
  return vertices * sizeof(Eigen::Vector3f) + triangles * sizeof(std::array<std::uint32_t, 3>);
}

}  // namespace

std::optional<fs::path> meshCacheDir() { return cacheDir(); }

bool meshCacheable(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".ply" || extension == ".stl";
}

std::string meshCacheName(const std::string& file_bytes) { return nameFor(FileKey(file_bytes)); }

std::optional<LocalMesh> readMeshCache(const fs::path& dir, const std::string& file_bytes) {
  const FileKey key(file_bytes);
  const fs::path path = dir / nameFor(key);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  Header h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof(h))) return std::nullopt;
  const Header want = headerFor(key, h.vertex_count, h.triangle_count);
  if (std::memcmp(&h, &want, sizeof(h)) != 0) return std::nullopt;
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec || h.vertex_count > size || h.triangle_count > size) return std::nullopt;  // no overflow below
  if (size != sizeof(Header) + payloadBytes(h.vertex_count, h.triangle_count)) return std::nullopt;
  LocalMesh mesh;
  mesh.vertices_m.resize(h.vertex_count);
  mesh.triangles.resize(h.triangle_count);
  in.read(reinterpret_cast<char*>(mesh.vertices_m.data()), std::streamsize(h.vertex_count * sizeof(Eigen::Vector3f)));
  in.read(reinterpret_cast<char*>(mesh.triangles.data()),
          std::streamsize(h.triangle_count * sizeof(std::array<std::uint32_t, 3>)));
  if (!in) return std::nullopt;
  for (const auto& t : mesh.triangles) {
    if (t[0] >= h.vertex_count || t[1] >= h.vertex_count || t[2] >= h.vertex_count) return std::nullopt;
  }
  markCacheFileUsed(path);
  return mesh;
}

void writeMeshCache(const fs::path& dir, const std::string& file_bytes, const LocalMesh& mesh,
                    std::uintmax_t limit_bytes) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "vertices are written as 3 floats");
  static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t), "triangles as 3 uint32");
  const FileKey key(file_bytes);
  writeCacheFile(
      dir / nameFor(key),
      [&](std::ostream& out) {
        const Header h = headerFor(key, mesh.vertices_m.size(), mesh.triangles.size());
        out.write(reinterpret_cast<const char*>(&h), sizeof(h));
        out.write(reinterpret_cast<const char*>(mesh.vertices_m.data()),
                  std::streamsize(mesh.vertices_m.size() * sizeof(Eigen::Vector3f)));
        out.write(reinterpret_cast<const char*>(mesh.triangles.data()),
                  std::streamsize(mesh.triangles.size() * sizeof(std::array<std::uint32_t, 3>)));
        return bool(out);
      },
      limit_bytes);
}

}  // namespace climbsim::scene
