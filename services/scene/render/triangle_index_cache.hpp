#pragma once
/// @file
/// The rasteriser's index of a large static mesh, kept between runs in the cache directory
/// (climbsim/cache_files.hpp) beside the copies of the mesh files. Building the default pylon's
/// index of 2 million triangles takes about half a second of CPU at every start of the scene
/// and of `solo` (centroids, Morton codes, the sort, the batches); reading its copy takes a
/// tenth of that.
///
/// A copy is found by what the index is built from: the counts and a hash of the bytes of the
/// vertices, the triangles and the slots, and the index's layout (leaf size, branching, lanes).
/// So a copy holds the very index the build would give, byte for byte, and the depth images
/// are the same with or without it. A copy cut short or not ours is passed over and the index
/// built (and written) again.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "triangle_index.hpp"

namespace climbsim::scene {

/// Fewest triangles whose index is kept (a smaller index builds in a few milliseconds).
constexpr std::size_t kIndexCacheMinTriangles = std::size_t(1) << 16;

/// The copy's file name for these inputs: "<hash>-<triangles>.index".
std::string triangleIndexCacheName(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle);

/// TriangleIndex(mesh_F, slot_of_triangle), read from `dir` when it holds a whole copy made from
/// the same inputs; else built and, with `dir` set and at least kIndexCacheMinTriangles
/// triangles, written there (climbsim::writeCacheFile: whole or not at all, the directory kept
/// under its limit). nullopt `dir`: built, nothing read or written.
TriangleIndex cachedTriangleIndex(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle,
                                  const std::optional<std::filesystem::path>& dir);

}  // namespace climbsim::scene
