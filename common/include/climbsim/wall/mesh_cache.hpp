#pragma once
/// @file
/// A binary copy of what assimp read from a self-contained mesh file (PLY, STL), kept between
/// runs so that a run does not parse the same millions of triangles again. assimp reads the
/// default pylon's 2 million triangles in about 0.5 s, and a distributed run reads them three
/// times (the launcher's start check, the scene, the drive); the copy loads in some 30 ms.
///
/// A copy is found by the mesh file's bytes (their size and a 64-bit hash), never by its name
/// or time: an edited or replaced file is read by assimp again, and so is every file after an
/// update of assimp. The copy holds exactly the vertices and triangles assimp gave, so a run is
/// bit for bit the same with or without it.
///
/// Where: climbsim/cache_files.hpp's directory (`$CLIMBSIM_MESH_CACHE`, `off` turns the copies
/// off), shared with the rasteriser's indices and kept under `kMeshCacheBytes` with them: the
/// least recently used copies go first. A directory that cannot be written, or a copy that is
/// cut short or not ours, only costs the assimp read.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "climbsim/cache_files.hpp"
#include "climbsim/wall/mesh_file.hpp"

namespace climbsim::scene {

/// Most bytes the copies may take together [B] (climbsim::kCacheBytes).
constexpr std::uintmax_t kMeshCacheBytes = kCacheBytes;

/// The cache directory (climbsim::cacheDir); nullopt when the copies are off or there is no home.
std::optional<std::filesystem::path> meshCacheDir();

/// Whether assimp's reading of `path` depends on its bytes alone (PLY and STL; OBJ, glTF and
/// COLLADA may read further files), so that the bytes can name the copy.
bool meshCacheable(const std::string& path);

/// The copy's file name for a mesh file of these bytes: "<hash>-<size>.mesh".
std::string meshCacheName(const std::string& file_bytes);

/// The copy in `dir` for these bytes, its vertices and triangles (LocalMesh::file left empty);
/// nullopt if there is none or it is not whole. A hit marks the copy as just used.
std::optional<LocalMesh> readMeshCache(const std::filesystem::path& dir, const std::string& file_bytes);

/// Writes the copy of `mesh` for these bytes into `dir` (a new file renamed into place, so that
/// processes reading and writing at once never see half a copy), then removes the least
/// recently used copies beyond `limit_bytes`. Failures are silent: the copy is only a shortcut.
void writeMeshCache(const std::filesystem::path& dir, const std::string& file_bytes, const LocalMesh& mesh,
                    std::uintmax_t limit_bytes = kMeshCacheBytes);

}  // namespace climbsim::scene
