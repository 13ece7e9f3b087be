#include "triangle_index_cache.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <ostream>
#include <string_view>

#include "climbsim/cache_files.hpp"

namespace climbsim::scene {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[16] = "climbsim-index2";
/// The batches start at a multiple of this in the file (and so in its mapping): a cache line.
constexpr std::uint64_t kBatchAlignment = 64;

template <typename T>
std::uint64_t hashOf(const std::vector<T>& v) {
  return std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)));
}

/// What an index is built from, and how: a copy is the index of these inputs only.
struct Inputs {
  std::uint32_t layout[4];  ///< leaf triangles, branching, batch lanes, sizeof(Leaf)
  std::uint64_t vertex_count;
  std::uint64_t triangle_count;
  std::uint64_t slot_count;
  std::uint64_t vertex_hash;
  std::uint64_t triangle_hash;
  std::uint64_t slot_hash;

  std::uint64_t combined() const {
    // splitmix64's finaliser over the three hashes and the counts, one after the other.
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (const std::uint64_t x : {vertex_hash, triangle_hash, slot_hash, vertex_count, triangle_count, slot_count}) {
      h ^= x + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
      h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
      h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
      h ^= h >> 31;
    }
    return h;
  }
};

/// The copy's layout: this header, the node count of each level (level_count of them), zeros up
/// to a multiple of kBatchAlignment, then the batches' floats, the batches' boxes, the leaves and
/// each level's nodes, in the machine's byte order (a copy is only read where it was written).
struct Header {
  char magic[16];
  Inputs inputs;
  std::uint64_t batch_floats;
  std::uint64_t batch_boxes;
  std::uint64_t leaves;
  std::uint64_t level_count;
};

Inputs inputsOf(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slots) {
  Inputs in{};
  in.layout[0] = TriangleIndex::kLeafTriangles;
  in.layout[1] = TriangleIndex::kBranching;
  in.layout[2] = TriangleIndex::kBatchLanes;
  in.layout[3] = sizeof(TriangleIndex::Leaf);
  in.vertex_count = mesh_F.vertices_m.size();
  in.triangle_count = mesh_F.triangles.size();
  in.slot_count = slots.size();
  in.vertex_hash = hashOf(mesh_F.vertices_m);
  in.triangle_hash = hashOf(mesh_F.triangles);
  in.slot_hash = hashOf(slots);
  return in;
}

std::string nameOf(const Inputs& in) {
  char name[64];
  std::snprintf(name, sizeof(name), "%016llx-%llu.index", static_cast<unsigned long long>(in.combined()),
                static_cast<unsigned long long>(in.triangle_count));
  return name;
}

/// Where the batches start: after the header and the level counts, aligned.
std::uint64_t batchOffset(std::uint64_t level_count) {
  const std::uint64_t end = sizeof(Header) + level_count * sizeof(std::uint64_t);
  return (end + kBatchAlignment - 1) / kBatchAlignment * kBatchAlignment;
}

/// A read-only private mapping of a whole file, unmapped with its last owner.
std::shared_ptr<const void> mapFile(const fs::path& path, std::uint64_t& size) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return nullptr;
  struct stat st {};
  void* base = MAP_FAILED;
  if (::fstat(fd, &st) == 0 && st.st_size > 0) {
    size = static_cast<std::uint64_t>(st.st_size);
    base = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  }
  ::close(fd);
  if (base == MAP_FAILED) return nullptr;
  return std::shared_ptr<const void>(base, [size](const void* p) { ::munmap(const_cast<void*>(p), size); });
}

template <typename T>
void copyArray(const char*& at, std::vector<T>& v, std::uint64_t count) {
  v.resize(count);
  std::memcpy(static_cast<void*>(v.data()), at, count * sizeof(T));
  at += count * sizeof(T);
}

template <typename T>
void writeArray(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}

}  // namespace

/// Writes and reads a TriangleIndex's members (its friend).
struct TriangleIndexFile {
  // Eigen's fixed-size vectors and boxes hold their coefficients and nothing else (no pointer),
  // so the parts are written and hashed as their bytes (as the mesh copies are).
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && sizeof(Eigen::AlignedBox3f) == 6 * sizeof(float),
                "the index's boxes are written as 6 floats");
  static_assert(sizeof(TriangleIndex::Leaf) == 6 * sizeof(float) + 3 * sizeof(std::uint32_t) &&
                    sizeof(TriangleIndex::Node) == 6 * sizeof(float) + 2 * sizeof(std::uint32_t),
                "a leaf and a node are written without padding");

  static bool write(std::ostream& out, const TriangleIndex& index, const Inputs& inputs) {
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof(kMagic));
    h.inputs = inputs;
    h.batch_floats = index.batches_F_.size();
    h.batch_boxes = index.batch_boxes_F_.size();
    h.leaves = index.leaves_.size();
    h.level_count = index.levels_.size();
    out.write(reinterpret_cast<const char*>(&h), sizeof(h));
    for (const auto& level : index.levels_) {
      const std::uint64_t nodes = level.size();
      out.write(reinterpret_cast<const char*>(&nodes), sizeof(nodes));
    }
    const std::uint64_t padding = batchOffset(h.level_count) - sizeof(Header) - h.level_count * sizeof(std::uint64_t);
    out.write(std::string(padding, '\0').data(), std::streamsize(padding));
    writeArray(out, index.batches_F_);
    writeArray(out, index.batch_boxes_F_);
    writeArray(out, index.leaves_);
    for (const auto& level : index.levels_) writeArray(out, level);
    return bool(out);
  }

  /// The index in `path` if it is a whole copy made from `inputs`, its parts consistent: its
  /// batches left in the file's mapping (no copy; the pages are the page cache's), the rest copied.
  static std::optional<TriangleIndex> read(const fs::path& path, const Inputs& inputs, std::uint32_t max_slot) {
    std::uint64_t size = 0;
    std::shared_ptr<const void> mapped = mapFile(path, size);
    if (!mapped || size < sizeof(Header)) return std::nullopt;
    const char* const base = static_cast<const char*>(mapped.get());
    Header h{};
    std::memcpy(&h, base, sizeof(h));
    if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0 || std::memcmp(&h.inputs, &inputs, sizeof(Inputs)) != 0) {
      return std::nullopt;
    }
    if (h.level_count > 64 || h.batch_floats > size || h.batch_boxes > size || h.leaves > size ||
        batchOffset(h.level_count) > size) {
      return std::nullopt;
    }
    std::vector<std::uint64_t> level_nodes(h.level_count);
    std::memcpy(level_nodes.data(), base + sizeof(Header), h.level_count * sizeof(std::uint64_t));
    std::uint64_t expected = batchOffset(h.level_count) + h.batch_floats * sizeof(float) +
                             h.batch_boxes * sizeof(Eigen::AlignedBox3f) + h.leaves * sizeof(TriangleIndex::Leaf);
    for (const std::uint64_t nodes : level_nodes) {
      if (nodes > size) return std::nullopt;
      expected += nodes * sizeof(TriangleIndex::Node);
    }
    if (expected != size || h.batch_floats != h.batch_boxes * TriangleIndex::kBatchFloats) return std::nullopt;

    TriangleIndex index;
    index.triangle_count_ = inputs.triangle_count;
    const char* at = base + batchOffset(h.level_count);
    index.batch_data_F_ = reinterpret_cast<const float*>(at);
    at += h.batch_floats * sizeof(float);
    copyArray(at, index.batch_boxes_F_, h.batch_boxes);
    copyArray(at, index.leaves_, h.leaves);
    index.levels_.resize(h.level_count);
    for (std::size_t l = 0; l < h.level_count; ++l) copyArray(at, index.levels_[l], level_nodes[l]);
    index.mapped_ = std::move(mapped);
    // Every reference in range: the walk and the kernels index by them unchecked.
    for (const auto& leaf : index.leaves_) {
      if (std::uint64_t(leaf.first_batch) + leaf.batch_count > h.batch_boxes || leaf.slot > max_slot) {
        return std::nullopt;
      }
    }
    for (std::size_t l = 0; l < index.levels_.size(); ++l) {
      const std::uint64_t below = l == 0 ? index.leaves_.size() : index.levels_[l - 1].size();
      for (const auto& node : index.levels_[l]) {
        if (std::uint64_t(node.first_child) + node.child_count > below) return std::nullopt;
      }
    }
    return index;
  }
};

std::string triangleIndexCacheName(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle) {
  return nameOf(inputsOf(mesh_F, slot_of_triangle));
}

TriangleIndex cachedTriangleIndex(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle,
                                  const std::optional<fs::path>& dir) {
  if (!dir || mesh_F.triangles.size() < kIndexCacheMinTriangles) return TriangleIndex(mesh_F, slot_of_triangle);
  const Inputs inputs = inputsOf(mesh_F, slot_of_triangle);
  const fs::path path = *dir / nameOf(inputs);
  const std::uint32_t max_slot =
      slot_of_triangle.empty() ? 0 : *std::max_element(slot_of_triangle.begin(), slot_of_triangle.end());
  if (auto copy = TriangleIndexFile::read(path, inputs, max_slot)) {
    markCacheFileUsed(path);
    return std::move(*copy);
  }
  TriangleIndex index(mesh_F, slot_of_triangle);
  writeCacheFile(path, [&](std::ostream& out) { return TriangleIndexFile::write(out, index, inputs); });
  return index;
}

}  // namespace climbsim::scene
