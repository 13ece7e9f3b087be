#pragma once
/// @file
/// Mesh files through assimp: an aiScene built in code, written with Assimp::Exporter, and
/// read back with Assimp::Importer to check what was written.

#include <string>

#include "climbsim/wall_patches/surface_mesh.hpp"

namespace climbsim::surface {

/// assimp exporter id for the file name's extension: .ply binary PLY ("plyb"), .stl binary
/// STL ("stlb"), .obj ("obj", with a .mtl beside it), .gltf ("gltf2"), .glb ("glb2"), .dae
/// ("collada"). Throws ConfigError naming the file for any other extension.
std::string exportFormatFor(const std::string& path);

/// Writes `mesh` (one mesh, one default material, root node with identity transform).
/// Throws ConfigError "<path>: ..." when assimp cannot write it.
void writeMesh(const std::string& path, const SurfaceMesh& mesh);

/// Reads every mesh of a file with assimp (triangulated, node transforms applied) into one
/// mesh. Throws ConfigError "<path>: ..." when assimp cannot read it.
SurfaceMesh readMesh(const std::string& path);

/// Writes `mesh`, reads the file back and throws ConfigError unless it holds the same
/// number of triangles.
void writeMeshChecked(const std::string& path, const SurfaceMesh& mesh);

}  // namespace climbsim::surface
