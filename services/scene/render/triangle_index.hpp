#pragma once
/// @file
/// The rasteriser's spatial index of one rigid set of triangles (the static wall, or one
/// moving body in its own frame F): triangles sorted along a Morton curve of their centroids
/// into leaves of at most 64, under a tree of axis-aligned boxes with 8 children per node. A
/// depth frame visits only the leaves whose box meets the camera's view volume, whatever the
/// camera's orientation. Each leaf stores its triangles' corners in batches of 16 laid out
/// for vector lanes (x0[16] y0[16] z0[16] x1[16] ... z2[16], 36 bytes per triangle), so that
/// a batch is transformed and rasterised without gathering.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene {

/// A view volume as TriangleIndex tests boxes against it: the box |x| <= half_x,
/// |y| <= half_y, z_min <= z <= z_max of a frame C, boxes of frame F mapped by
/// p_C = A_CF p_F + a_CF.
struct ViewVolume {
  Eigen::Matrix3d A_CF;
  Eigen::Vector3d a_CF;
  double half_x, half_y, z_min, z_max;
  Eigen::Matrix3d abs_A = A_CF.cwiseAbs();

  /// Where the box of the mapped box_F lies: 0 out of the volume (so box_F is: conservative),
  /// 1 meeting it, 2 wholly in it. Inlined: it runs for every node, leaf and batch in view.
  [[gnu::always_inline]] int place(const Eigen::AlignedBox3f& box_F) const {
    Eigen::Vector3d c, e;
    map(box_F, c, e);
    return placeMapped(c, e);
  }
  /// The box of the mapped box_F: its centre c = A_CF c_F + a_CF and half extents e = |A_CF| h_F.
  [[gnu::always_inline]] void map(const Eigen::AlignedBox3f& box_F, Eigen::Vector3d& c, Eigen::Vector3d& e) const {
    c = A_CF * box_F.center().cast<double>() + a_CF;
    e = abs_A * (0.5 * box_F.sizes().cast<double>());
  }
  /// place() of the box of the mapped box given as its centre c = A_CF c_F + a_CF and its half
  /// extents e = |A_CF| h_F (for a caller that uses them too).
  [[gnu::always_inline]] int placeMapped(const Eigen::Vector3d& c, const Eigen::Vector3d& e) const {
    if (!(std::abs(c.x()) <= half_x + e.x() && std::abs(c.y()) <= half_y + e.y() && c.z() - e.z() <= z_max &&
          c.z() + e.z() >= z_min)) {
      return 0;
    }
    return std::abs(c.x()) + e.x() <= half_x && std::abs(c.y()) + e.y() <= half_y && c.z() + e.z() <= z_max &&
                   c.z() - e.z() >= z_min
               ? 2
               : 1;
  }
};

class TriangleIndex {
 public:
  static constexpr std::uint32_t kLeafTriangles = 64;
  static constexpr std::uint32_t kBranching = 8;
  static constexpr int kBatchLanes = 16; ///< triangles per batch; a short batch repeats its last triangle
  static constexpr int kBatchFloats = 9 * kBatchLanes;

  struct Leaf {
    Eigen::AlignedBox3f box_F;
    std::uint32_t slot = 0;  ///< the part slot shared by all triangles of the leaf
    std::uint32_t first_batch = 0;
    std::uint32_t batch_count = 0;
  };

  struct Node {
    Eigen::AlignedBox3f box_F;
    std::uint32_t first_child = 0;  ///< into the level below (or into leaves() for level 0)
    std::uint32_t child_count = 0;
  };

  /// An empty index.
  TriangleIndex() = default;
  /// Moved, never copied: batchData_F points into the index's own storage.
  TriangleIndex(TriangleIndex&&) noexcept = default;
  TriangleIndex& operator=(TriangleIndex&&) noexcept = default;
  TriangleIndex(const TriangleIndex&) = delete;
  TriangleIndex& operator=(const TriangleIndex&) = delete;
  /// mesh_F: triangles in frame F; slot_of_triangle: one small integer per triangle (the
  /// part's slot); leaves never mix slots. Preconditions (checked by the caller): indices in
  /// range, one slot per triangle.
  TriangleIndex(const TriangleMesh& mesh_F, const std::vector<std::uint32_t>& slot_of_triangle);

  const std::vector<Leaf>& leaves() const { return leaves_; }
  /// Batch b's corner coordinates in F [m]: kBatchFloats floats from batchData_F(b).
  const float* batchData_F(std::uint32_t b) const { return batch_data_F_ + static_cast<std::size_t>(b) * kBatchFloats; }
  /// Batch b's box of its triangles' corners in F [m] (to cull a batch of a leaf that lies
  /// partly in view before the kernel sets it up).
  const Eigen::AlignedBox3f& batchBox_F(std::uint32_t b) const { return batch_boxes_F_[b]; }
  std::size_t triangleCount() const { return triangle_count_; }

  /// Calls visit(const Leaf&) for every leaf whose box, mapped into the frame C of the view
  /// volume by p_C = A_CF p_F + a_CF, may meet the box |x| <= half_x, |y| <= half_y,
  /// z_min <= z <= z_max (conservative: the box of the mapped box is tested); a visit that
  /// takes (const Leaf&, bool) is told too whether that box of the mapped box lies wholly in it,
  /// one that takes (const Leaf&, bool, c, e) also that box's centre c = A_CF c_F + a_CF and half
  /// extents e = |A_CF| h_F (ViewVolume::placeMapped).
  template <typename Visit>
  void forEachLeafInView(const Eigen::Matrix3d& A_CF, const Eigen::Vector3d& a_CF, double half_x, double half_y,
                         double z_min, double z_max, Visit&& visit) const;

 private:
  friend struct TriangleIndexFile;  // triangle_index_cache.cpp: writes and reads these members

  /// The batches' floats: batches_F_.data() for a built index, or a read-only mapping of its
  /// copy (triangle_index_cache.cpp), which `mapped_` keeps (the page cache's pages, shared by
  /// every process that maps the same copy).
  std::vector<float> batches_F_;
  const float* batch_data_F_ = nullptr;
  std::shared_ptr<const void> mapped_;
  std::vector<Eigen::AlignedBox3f> batch_boxes_F_;
  std::size_t triangle_count_ = 0;
  std::vector<Leaf> leaves_;
  std::vector<std::vector<Node>> levels_;  ///< levels_[0] over leaves, levels_.back() the roots
};

template <typename Visit>
void TriangleIndex::forEachLeafInView(const Eigen::Matrix3d& A_CF, const Eigen::Vector3d& a_CF, double half_x,
                                      double half_y, double z_min, double z_max, Visit&& visit) const {
  const ViewVolume view{A_CF, a_CF, half_x, half_y, z_min, z_max};
  if (levels_.empty()) return;
  // Explicit stack of (level, node index); the tree is at most ~8 levels deep.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;
  stack.reserve(64);
  const auto top = static_cast<std::uint32_t>(levels_.size() - 1);
  for (std::uint32_t i = 0; i < levels_[top].size(); ++i) stack.emplace_back(top, i);
  while (!stack.empty()) {
    const auto [level, index] = stack.back();
    stack.pop_back();
    const Node& node = levels_[level][index];
    if (view.place(node.box_F) == 0) continue;
    for (std::uint32_t k = node.first_child; k < node.first_child + node.child_count; ++k) {
      if (level == 0) {
        Eigen::Vector3d c, e;
        view.map(leaves_[k].box_F, c, e);
        const int place = view.placeMapped(c, e);
        if (place == 0) continue;
        if constexpr (std::is_invocable_v<Visit, const Leaf&, bool, const Eigen::Vector3d&, const Eigen::Vector3d&>) {
          visit(leaves_[k], place == 2, c, e);
        } else if constexpr (std::is_invocable_v<Visit, const Leaf&, bool>) {
          visit(leaves_[k], place == 2);
        } else {
          visit(leaves_[k]);
        }
      } else {
        stack.emplace_back(level - 1, k);
      }
    }
  }
}

}  // namespace climbsim::scene
