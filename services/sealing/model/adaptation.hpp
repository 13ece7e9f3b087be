#pragma once
/// @file
/// The sealing adaptation of DESIGN.md §3.2, twice: the paper's loop (the test oracle) and
/// the production algorithm. Both compute the same fixpoint, bit for bit.
///
/// Neighbourhood: the 8-neighbourhood of the pixel grid restricted to sealing pixels (of any
/// segment: the strips are one continuous sealing, so the adaptation runs across junctions).
/// The largest height step between neighbours is the slope times their centre distance:
///   step_orth_m = max_slope * s          (left, right, up, down)
///   step_diag_m = max_slope * s * sqrt 2 (diagonals)
/// so the physics does not change with the resolution s.
///
/// The fixpoint: h_s is the least function >= h_g with h_s(n) - step(n, p) <= h_s(p) for all
/// neighbouring sealing pixels n, p, i.e.
///   h_s(p) = max(h_g(p), max_q (h_g(q) - max_slope * d(p, q)))
/// with d the shortest 8-connected path through sealing pixels. In floating point both
/// algorithms evaluate exactly the update h(p) <- max(h(p), h(n) - step(n, p)) in double, so
/// both reach the least fixpoint of that update: the same doubles.
///
/// The travel limit and the gaps are applied afterwards (leakage.hpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "strip_masks.hpp"

namespace climbsim::sealing {

/// The 8 neighbour offsets and their steps, shared by the oracle and the production path.
struct Neighbourhood {
  /// (d_row, d_col) of the 8 neighbours; entries 0..3 are orthogonal, 4..7 diagonal.
  static constexpr std::array<std::array<int, 2>, 8> kOffsets{
      {{{0, 1}}, {{1, 0}}, {{0, -1}}, {{-1, 0}}, {{1, 1}}, {{1, -1}}, {{-1, 1}}, {{-1, -1}}}};
  /// Largest height step to an orthogonal (k < 4) or diagonal neighbour [m].
  std::array<double, 8> step_m{};

  /// Steps for `max_slope` [m/m] (> 0) on pixels of `pixel_size_m` [m].
  Neighbourhood(double max_slope, double pixel_size_m);
};

/// The paper's algorithm (test oracle): every pass raises each sealing pixel to the highest
/// of (its value, each neighbour's value of the previous pass minus the step); repeat until
/// a pass changes nothing. `ground_m` is h_g per raster pixel (W * H). Returns h_s per
/// sealing index (StripMasks::sealingPixels order) [m]; `passes` (if given) receives the
/// number of passes including the last one that changed nothing.
std::vector<double> adaptNaive(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<float>& ground_m,
                               int* passes = nullptr);

/// Thrown by the adapters for a ground height that is not finite.
struct NonFiniteGround : std::invalid_argument {
  std::uint32_t raster;  ///< the raster pixel (row * W + col)
  float value;
  NonFiniteGround(std::uint32_t raster_pixel, float v)
      : std::invalid_argument("ground height not finite"), raster(raster_pixel), value(v) {}
};

/// A part of the sealing's pixel graph with an order of its own: local index i stands for
/// sealing index `sealing_index[i]`, and `neighbours[8 i + j]` is the local index of its
/// neighbour at Neighbourhood::kOffsets[j], or -1 (outside the strips or outside the part).
/// The whole sealing in sealing-index order is one such part (SealingAdapter); a shard's
/// region ordered by distance from its segments is another (shard_region.hpp).
struct SealingSubgraph {
  std::vector<std::uint32_t> sealing_index;
  std::vector<std::int32_t> neighbours;
  std::size_t size() const { return sealing_index.size(); }
};

/// The whole sealing of `masks` in sealing-index order.
SealingSubgraph wholeSealingGraph(const StripMasks& masks);

/// The production algorithm: a Dijkstra-like propagation from the highest values down, with
/// a bucket queue (Dial) of buckets one orthogonal step wide instead of a heap. Only pixels
/// that can raise a neighbour enter the queue; a pixel raised by a bucket's pixel lands in a
/// later bucket, so each pixel's neighbours are relaxed about once per raise instead of once
/// per pass over the whole sealing. Any order that relaxes every raised pixel again reaches
/// the same least fixpoint; the buckets only keep the repeats few.
///
/// It runs on a SealingSubgraph and only on its first `active` local pixels (the others and
/// the edges to them do not exist for that call): the least fixpoint of the update on that
/// induced subgraph. Its value at a pixel p is the largest float-evaluated walk value
/// h_g(q) - step - step ... over walks q -> p inside the subgraph, so it equals the whole
/// sealing's value wherever no walk leaving the subgraph can beat it (shard_region.hpp).
class SubgraphAdapter {
 public:
  /// `graph` is a part of the sealing of `masks` (only its raster positions are kept).
  SubgraphAdapter(SealingSubgraph graph, const StripMasks& masks, const Neighbourhood& nbh);

  /// h_s per local index i < active [m] into `local_m` (resized to `active`) for the ground
  /// heights h_g per raster pixel (W * H) [m]; NonFiniteGround if one of those it reads is not
  /// finite. Not reentrant: the adapter keeps its queue between calls (one adapter per thread).
  void adapt(const std::vector<float>& ground_m, std::size_t active, std::vector<double>& local_m) const;

  const SealingSubgraph& graph() const { return graph_; }
  const Neighbourhood& neighbourhood() const { return nbh_; }

 private:
  SealingSubgraph graph_;
  std::vector<std::uint32_t> raster_of_;  ///< raster pixel of each local index
  Neighbourhood nbh_;
  /// Storage of the queue, kept between frames so that a frame allocates nothing.
  struct Scratch {
    std::vector<std::vector<std::uint32_t>> buckets;
    std::vector<std::uint8_t> done;
  };
  mutable Scratch scratch_;
};

/// The production algorithm on the whole sealing.
class SealingAdapter {
 public:
  SealingAdapter(const StripMasks& masks, const Neighbourhood& nbh);

  /// h_s per sealing index [m] for the ground heights h_g per raster pixel (W * H) [m].
  std::vector<double> adapt(const std::vector<float>& ground_m) const;

  /// As adapt(), into `sealing_m` (resized), reusing its storage. Not reentrant (one
  /// adapter per thread).
  void adapt(const std::vector<float>& ground_m, std::vector<double>& sealing_m) const;

 private:
  SubgraphAdapter whole_;
};

}  // namespace climbsim::sealing
