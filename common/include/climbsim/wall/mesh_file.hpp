#pragma once
/// @file
/// Mesh files of scene parts, read with assimp (PLY, OBJ, STL, glTF 2, COLLADA and whatever
/// else assimp reads).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// The triangles of one mesh file in the frame of the part that carries it [m]: the file's
/// node hierarchy is flattened (each mesh's vertices multiplied by the product of its node's
/// and all ancestors' transforms), polygons are triangulated, points and lines dropped.
struct LocalMesh {
  std::string file;  ///< path as resolved from the scene file
  std::vector<Eigen::Vector3f> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Reads `path` with assimp, or a PLY or STL file from the copy of an earlier read of the same
/// bytes (climbsim/wall/mesh_cache.hpp). `where` is the "<scene file>:<line>" of the part naming it and
/// `attribute` the attribute text as written (file="..."), for the message of the
/// ConfigError thrown when assimp cannot read the file or it holds no triangle.
LocalMesh loadMeshFile(const std::string& path, const std::string& where, const std::string& attribute);

}  // namespace climbsim::scene
