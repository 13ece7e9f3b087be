#include "climbsim/wall_patches/mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <memory>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "climbsim/errors.hpp"

namespace climbsim::surface {
namespace {

std::string lowerExtension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// aiScene owns what it points to and frees it with delete / delete[].
std::unique_ptr<aiScene> buildScene(const SurfaceMesh& mesh) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("wall_patch");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned int[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  const aiString material_name("concrete");
  scene->mMaterials[0]->AddProperty(&material_name, AI_MATKEY_NAME);
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh* out = scene->mMeshes[0];
  out->mName = "wall_patch";
  out->mMaterialIndex = 0;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mNumVertices = static_cast<unsigned int>(mesh.vertices_m.size());
  out->mVertices = new aiVector3D[out->mNumVertices];
  for (unsigned int v = 0; v < out->mNumVertices; ++v)
    out->mVertices[v] = aiVector3D(mesh.vertices_m[v].x(), mesh.vertices_m[v].y(), mesh.vertices_m[v].z());
  out->mNumFaces = static_cast<unsigned int>(mesh.triangles.size());
  out->mFaces = new aiFace[out->mNumFaces];
  for (unsigned int f = 0; f < out->mNumFaces; ++f) {
    out->mFaces[f].mNumIndices = 3;
    out->mFaces[f].mIndices = new unsigned int[3]{mesh.triangles[f][0], mesh.triangles[f][1], mesh.triangles[f][2]};
  }
  return scene;
}

void appendNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, SurfaceMesh& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned int m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const auto base = static_cast<std::uint32_t>(out.vertices_m.size());
    for (unsigned int v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices_m.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  for (unsigned int c = 0; c < node.mNumChildren; ++c) appendNode(scene, *node.mChildren[c], transform, out);
}

}  // namespace

std::string exportFormatFor(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == "ply") return "plyb";
  if (ext == "stl") return "stlb";
  if (ext == "obj") return "obj";
  if (ext == "gltf") return "gltf2";
  if (ext == "glb") return "glb2";
  if (ext == "dae") return "collada";
  throw ConfigError(path + ": unknown mesh extension '" + ext + "' (ply, stl, obj, gltf, glb, dae)");
}

void writeMesh(const std::string& path, const SurfaceMesh& mesh) {
  const std::string format = exportFormatFor(path);
  if (mesh.triangles.empty()) throw ConfigError(path + ": refusing to write an empty mesh");
  const std::unique_ptr<aiScene> scene = buildScene(mesh);
  Assimp::Exporter exporter;
  if (exporter.Export(scene.get(), format, path) != AI_SUCCESS)
    throw ConfigError(path + ": assimp could not write it (" + format + "): " + exporter.GetErrorString());
}

SurfaceMesh readMesh(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw ConfigError(path + ": assimp could not read it: " + importer.GetErrorString());
  SurfaceMesh out;
  appendNode(*scene, *scene->mRootNode, aiMatrix4x4(), out);
  return out;
}

void writeMeshChecked(const std::string& path, const SurfaceMesh& mesh) {
  writeMesh(path, mesh);
  const SurfaceMesh back = readMesh(path);
  if (back.triangles.size() != mesh.triangles.size())
    throw ConfigError(path + ": read back " + std::to_string(back.triangles.size()) + " triangles, wrote " +
                      std::to_string(mesh.triangles.size()));
}

}  // namespace climbsim::surface
