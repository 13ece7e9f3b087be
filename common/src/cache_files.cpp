#include "climbsim/cache_files.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace climbsim {
namespace fs = std::filesystem;

std::optional<fs::path> cacheDir() {
  if (const char* set = std::getenv("CLIMBSIM_MESH_CACHE"); set != nullptr && *set != '\0') {
    if (std::string_view(set) == "off") return std::nullopt;
    return fs::path(set);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg == '/') {
    return fs::path(xdg) / "climbsim" / "meshes";
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home == '/') {
    return fs::path(home) / ".cache" / "climbsim" / "meshes";
  }
  return std::nullopt;
}

bool writeCacheFile(const fs::path& path, const std::function<bool(std::ostream&)>& write,
                    std::uintmax_t limit_bytes) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) return false;
  // A name of its own for every writer, also for two threads of one process writing one copy.
  static std::atomic<unsigned> writes{0};
  const fs::path temporary =
      path.string() + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(writes.fetch_add(1));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    const bool written = out && write(out);
    out.close();
    if (!written || !out) {
      fs::remove(temporary, ec);
      return false;
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return false;
  }
  trimCacheDir(path.parent_path(), limit_bytes);
  return fs::exists(path, ec);
}

void trimCacheDir(const fs::path& dir, std::uintmax_t limit_bytes) {
  struct Copy {
    fs::file_time_type used;
    std::uintmax_t bytes;
    fs::path path;
  };
  std::vector<Copy> copies;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path extension = it->path().extension();
    if (extension != ".mesh" && extension != ".index") continue;
    std::error_code e1, e2;
    const auto bytes = it->file_size(e1);
    const auto used = it->last_write_time(e2);
    if (e1 || e2) continue;
    copies.push_back({used, bytes, it->path()});
    total += bytes;
  }
  if (total <= limit_bytes) return;
  std::sort(copies.begin(), copies.end(), [](const Copy& a, const Copy& b) { return a.used < b.used; });
  for (const auto& c : copies) {
    if (total <= limit_bytes) break;
    if (fs::remove(c.path, ec)) total -= c.bytes;
  }
}

void markCacheFileUsed(const fs::path& path) {
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
}

}  // namespace climbsim
