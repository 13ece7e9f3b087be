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

  triangle_count_ = n;
  batches_F_.reserve((n / kBatchLanes + 1) * kBatchFloats);
  std::size_t i = 0;
  while (i < n) {
    Leaf leaf;
    leaf.slot = slot_of_triangle[order[i]];
    leaf.first_batch = static_cast<std::uint32_t>(batches_F_.size() / kBatchFloats);
    std::size_t end = i;
    while (end < n && end - i < kLeafTriangles && slot_of_triangle[order[end]] == leaf.slot) ++end;
    for (std::size_t first = i; first < end; first += kBatchLanes) {
      const std::size_t base = batches_F_.size();
      batches_F_.resize(base + kBatchFloats);
      Eigen::AlignedBox3f& batch_box = batch_boxes_F_.emplace_back();
      for (int lane = 0; lane < kBatchLanes; ++lane) {
        const std::size_t t = order[std::min(first + lane, end - 1)];
        for (int corner = 0; corner < 3; ++corner) {
          const Eigen::Vector3f& p = mesh_F.vertices_m[mesh_F.triangles[t][corner]];
          leaf.box_F.extend(p);
          batch_box.extend(p);
          for (int axis = 0; axis < 3; ++axis) batches_F_[base + (3 * corner + axis) * kBatchLanes + lane] = p[axis];
        }
      }
      ++leaf.batch_count;
    }
    leaves_.push_back(leaf);
    i = end;
  }
  batches_F_.shrink_to_fit();
  batch_data_F_ = batches_F_.data();
  batch_boxes_F_.shrink_to_fit();

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
