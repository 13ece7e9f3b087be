#include "climbsim/wall/mesh_file.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <system_error>

#include "climbsim/errors.hpp"
#include "climbsim/wall/mesh_cache.hpp"

namespace climbsim::scene {
namespace {

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent_transform, LocalMesh& out) {
  // assimp's matrices act on column vectors like Eigen's: child to parent is parent * node.
  const aiMatrix4x4 transform = parent_transform * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const auto base = static_cast<std::uint32_t>(out.vertices_m.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices_m.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    appendNode(scene, *node.mChildren[c], transform, out);
  }
}

/// The file's bytes; nullopt if it cannot be read (assimp then says why).
std::optional<std::string> fileBytes(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) return std::nullopt;
  std::string bytes(size, '\0');
  if (!in.read(bytes.data(), std::streamsize(size)) || in.peek() != std::ifstream::traits_type::eof()) {
    return std::nullopt;  // it changed while read: assimp reads it
  }
  return bytes;
}

LocalMesh readWithAssimp(const std::string& path, const std::string& where, const std::string& attribute) {
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    // Files with only points or lines fail in the post-processing: read them raw to tell
    // an empty mesh from an unreadable file.
    Assimp::Importer raw;
    if (raw.ReadFile(path, 0) != nullptr) {
      throw ConfigError(where + ": " + attribute + ": empty mesh, no triangle in " + path);
    }
    std::string reason = importer.GetErrorString();
    if (!reason.empty() && reason.back() == '\n') reason.pop_back();
    throw ConfigError(where + ": " + attribute + ": assimp cannot read the mesh " + path + " (" + reason + ")");
  }
  LocalMesh mesh;
  mesh.file = path;
  appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  if (mesh.triangles.empty()) {
    throw ConfigError(where + ": " + attribute + ": empty mesh, no triangle in " + path);
  }
  for (const auto& v : mesh.vertices_m) {
    if (!v.allFinite()) {
      throw ConfigError(where + ": " + attribute + ": mesh " + path + " has a vertex that is not finite");
    }
  }
  return mesh;
}

}  // namespace

LocalMesh loadMeshFile(const std::string& path, const std::string& where, const std::string& attribute) {
  const auto dir = meshCacheable(path) ? meshCacheDir() : std::nullopt;
  const auto bytes = dir ? fileBytes(path) : std::nullopt;
  if (!bytes) return readWithAssimp(path, where, attribute);
  if (auto copy = readMeshCache(*dir, *bytes)) {
    copy->file = path;
    return std::move(*copy);
  }
  LocalMesh mesh = readWithAssimp(path, where, attribute);
  writeMeshCache(*dir, *bytes, mesh);
  return mesh;
}

}  // namespace climbsim::scene
