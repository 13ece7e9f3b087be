#pragma once
/// @file
/// The directory where climbsim keeps what it can compute again but need not: the binary
/// copies of mesh files (climbsim/wall/mesh_cache.hpp, `.mesh`) and the rasteriser's indices
/// of large static meshes (services/scene/render/triangle_index_cache.hpp, `.index`). Every
/// copy is found by a hash of what it was made from, never by a name or a time, so a copy is
/// either the very thing a run would compute or not used; losing the directory only costs time.
///
/// Where: `$CLIMBSIM_MESH_CACHE` (a directory; `off` turns every copy off), else
/// `$XDG_CACHE_HOME/climbsim/meshes`, else `$HOME/.cache/climbsim/meshes`.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>

namespace climbsim {

/// Most bytes the copies may take together [B] (1 GiB: the copies of some 8 scenes of the
/// default pylon's size, each its mesh and its index).
constexpr std::uintmax_t kCacheBytes = std::uintmax_t(1) << 30;

/// The directory by the rules above; nullopt when the copies are off or there is no home.
std::optional<std::filesystem::path> cacheDir();

/// Writes `path` whole or not at all: `write` fills a new file beside it (returning false, or
/// leaving the stream failed, abandons it), which is then renamed into place, so that processes
/// reading and writing at once never see half a copy. Creates the directory. Then removes the
/// least recently used copies of the directory beyond `limit_bytes` (trimCacheDir). Returns
/// whether the copy is in place; failures are silent: a copy is only a shortcut.
bool writeCacheFile(const std::filesystem::path& path, const std::function<bool(std::ostream&)>& write,
                    std::uintmax_t limit_bytes = kCacheBytes);

/// Removes the least recently used copies (`.mesh` and `.index` files, by modification time,
/// which markCacheFileUsed renews) until those in `dir` take at most `limit_bytes`.
void trimCacheDir(const std::filesystem::path& dir, std::uintmax_t limit_bytes = kCacheBytes);

/// Marks a copy as just used (its modification time), so that trimming keeps it longest.
void markCacheFileUsed(const std::filesystem::path& path);

}  // namespace climbsim
