#include "triangle_index.hpp"

#include <algorithm>
#include <numeric>

namespace climbsim::scene {

namespace {

// Spreads the low 21 bits of v so that two zero bits follow each of them.
std::uint64_t spreadBits3(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

TriangleIndex::TriangleIndex(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle) {
  const std::size_t n = mesh_F.triangles.size();
  if (n == 0) return;

  std::vector<Eigen::Vector3f> centroid(n);
  Eigen::AlignedBox3f bounds;
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = mesh_F.triangles[t];
    centroid[t] = (mesh_F.vertices_m[tri[0]] + mesh_F.vertices_m[tri[1]] + mesh_F.vertices_m[tri[2]]) / 3.0f;
    bounds.extend(centroid[t]);
  }
  const Eigen::Vector3f extent = bounds.sizes().cwiseMax(1e-9f);
  const float cells = static_cast<float>((1u << 21) - 1);
  std::vector<std::uint64_t> morton(n);
  for (std::size_t t = 0; t < n; ++t) {
    const Eigen::Vector3f q = ((centroid[t] - bounds.min()).cwiseQuotient(extent) * cells).cwiseMax(0.0f).cwiseMin(cells);
    morton[t] = spreadBits3(static_cast<std::uint64_t>(q.x())) | spreadBits3(static_cast<std::uint64_t>(q.y())) << 1 |
                spreadBits3(static_cast<std::uint64_t>(q.z())) << 2;
  }
  centroid.clear();
  centroid.shrink_to_fit();

  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (slot_of_triangle[a] != slot_of_triangle[b]) return slot_of_triangle[a] < slot_of_triangle[b];
    if (morton[a] != morton[b]) return morton[a] < morton[b];
    return a < b;
  });
  morton.clear();
  morton.shrink_to_fit();

  // local_of[v] is vertex v's index in the leaf being built when stamp[v] == that leaf.
  std::vector<std::uint32_t> stamp(mesh_F.vertices_m.size(), UINT32_MAX);
  std::vector<std::uint8_t> local_of(mesh_F.vertices_m.size(), 0);
  triangles_.reserve(n);
  vertices_F_.reserve(n / 2 + 3);
  std::size_t i = 0;
  while (i < n) {
    Leaf leaf;
    leaf.slot = slot_of_triangle[order[i]];
    leaf.first_vertex = static_cast<std::uint32_t>(vertices_F_.size());
    leaf.first_triangle = static_cast<std::uint32_t>(triangles_.size());
    const auto leaf_id = static_cast<std::uint32_t>(leaves_.size());
    while (i < n && leaf.triangle_count < kLeafTriangles && slot_of_triangle[order[i]] == leaf.slot) {
      std::array<std::uint8_t, 3> local{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh_F.triangles[order[i]][k];
        if (stamp[v] != leaf_id) {
          stamp[v] = leaf_id;
          local_of[v] = static_cast<std::uint8_t>(leaf.vertex_count++);
          vertices_F_.push_back(mesh_F.vertices_m[v]);
          leaf.box_F.extend(mesh_F.vertices_m[v]);
        }
        local[k] = local_of[v];
      }
      triangles_.push_back(local);
      ++leaf.triangle_count;
      ++i;
    }
    leaves_.push_back(leaf);
  }
  vertices_F_.shrink_to_fit();

  // Levels of 8-way nodes over consecutive children (consecutive along the Morton curve,
  // hence compact boxes), up to a few roots.
  std::vector<Eigen::AlignedBox3f> child_boxes;
  child_boxes.reserve(leaves_.size());
  for (const Leaf& leaf : leaves_) child_boxes.push_back(leaf.box_F);
  do {
    std::vector<Node> level;
    level.reserve(child_boxes.size() / kBranching + 1);
    for (std::size_t first = 0; first < child_boxes.size(); first += kBranching) {
      Node node;
      node.first_child = static_cast<std::uint32_t>(first);
      node.child_count = static_cast<std::uint32_t>(std::min<std::size_t>(kBranching, child_boxes.size() - first));
      for (std::uint32_t k = 0; k < node.child_count; ++k) node.box_F.extend(child_boxes[first + k]);
      level.push_back(node);
    }
    child_boxes.clear();
    for (const Node& node : level) child_boxes.push_back(node.box_F);
    levels_.push_back(std::move(level));
  } while (child_boxes.size() > kBranching);
}

}  // namespace climbsim::scene
