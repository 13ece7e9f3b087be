#pragma once
/// @file
/// The sealing adaptation of docs/design.md#sealing-and-leakage, twice: the paper's loop (the test
/// oracle) and the production algorithm. Both compute the same fixpoint, bit for bit.
///
/// Neighbourhood: the 8-neighbourhood of the sealing pixels and its height steps
/// (climbsim/shard_tiles/sealing_graph.hpp).
///
/// The fixpoint: h_s is the least function >= h_g (>= max(h_g, h_sup) with support heights)
/// with h_s(n) - step(n, p) <= h_s(p) for all
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

#include "climbsim/shard_tiles/depth_grid.hpp"
#include "climbsim/shard_tiles/pixel_runs.hpp"
#include "climbsim/shard_tiles/sealing_graph.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

/// The paper's algorithm (test oracle): every pass raises each sealing pixel to the highest
/// of (its value, each neighbour's value of the previous pass minus the step); repeat until
/// a pass changes nothing. `ground_m` is h_g per raster pixel (W * H). Returns h_s per
/// sealing index (StripMasks::sealingPixels order) [m]; `passes` (if given) receives the
/// number of passes including the last one that changed nothing. `supports` (sub-pixel
/// leakage), if given: a pixel with a support height h_sup starts at max(h_g, h_sup) instead.
std::vector<double> adaptNaive(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<float>& ground_m,
                               int* passes = nullptr, const SupportHeights* supports = nullptr);

/// Thrown by the adapters for a ground height that is not finite.
struct NonFiniteGround : std::invalid_argument {
  std::uint32_t raster;  ///< the raster pixel (row * W + col)
  float value;
  NonFiniteGround(std::uint32_t raster_pixel, float v)
      : std::invalid_argument("ground height not finite"), raster(raster_pixel), value(v) {}
};

/// The production algorithm: a Dijkstra-like propagation from the highest values down, with
/// a bucket queue (Dial) of buckets one orthogonal step wide instead of a heap. Only pixels
/// that can raise a neighbour enter the queue; a pixel raised by a bucket's pixel lands in a
/// later bucket, so each pixel's neighbours are relaxed about once per raise instead of once
/// per pass over the whole sealing. Any order that relaxes every raised pixel again reaches
/// the same least fixpoint; the buckets only keep the repeats few.
///
/// It runs on a set of sealing pixels given as runs (PixelRuns) and in place on an array per
/// sealing index of the whole sealing: the least fixpoint of the update on the subgraph the
/// runs induce. Its value at a pixel p is the largest float-evaluated walk value
/// h_g(q) - step - step ... over walks q -> p inside the runs, so it equals the whole
/// sealing's value wherever no walk leaving them can beat it (shard_region.hpp). A shard thus
/// reads and writes only the memory of its region's runs.
///
/// A floor F (the travel limit, leakage.hpp) starts every pixel at max(h_g, F) instead of h_g:
/// the least fixpoint above that is exactly max(h_s, F) of the unfloored one, the same doubles
/// (a walk from a pixel below F stays below F; the others are unchanged), but the pixels that
/// the floor already holds up are never queued. Support heights (sub-pixel leakage) raise the
/// start values the same way: a pixel of the runs with h_sup starts at max(h_g, F, h_sup), and
/// the walk values above start at h_sup instead of h_g there.
class RunAdapter {
 public:
  /// For the sealing of `masks` (only its neighbour links are kept).
  RunAdapter(const StripMasks& masks, const Neighbourhood& nbh);

  /// Adapts the pixels of `runs` in `height` (one value per sealing pixel of the whole
  /// sealing; resized to that if smaller) [m] to the ground heights h_g per raster pixel
  /// (W * H) [m] and the floor `floor_m` (-inf: none). Every sealing pixel outside `runs` next
  /// to one of them must hold NaN in `height` (it then neither raises nor is raised); the
  /// others outside are left as they are. NonFiniteGround if a ground height of the runs is not
  /// finite. `ground_s`, if given, receives h_g of the runs' pixels as doubles per sealing index
  /// (resized like `height`; read in the same pass): the leakage's gaps then read consecutive
  /// memory (h_g, not the support). `supports`, if given, raise the start values of their
  /// pixels that lie in the runs (the others are ignored). Not reentrant: the adapter keeps
  /// its queue between calls (one adapter per thread).
  void adapt(const std::vector<float>& ground_m, const PixelRuns& runs, double floor_m, std::vector<double>& height,
             std::vector<double>* ground_s = nullptr, const SupportHeights* supports = nullptr) const;

  const Neighbourhood& neighbourhood() const { return nbh_; }

 private:
  const StripMasks* masks_;  ///< the support heights' pixels to sealing indices
  NeighbourLinks links_;
  Neighbourhood nbh_;
  /// Storage of the queue and its flags, kept between frames so that a frame allocates nothing.
  struct Scratch {
    std::vector<std::vector<std::uint32_t>> buckets;
    std::vector<std::uint8_t> flag;  ///< per sealing index: queued as a raiser / done
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

  /// As adapt() with the floor `floor_m` [m], the start values raised by `supports` if given,
  /// and, if given, h_g per sealing index into `ground_s` (RunAdapter).
  void adapt(const std::vector<float>& ground_m, double floor_m, std::vector<double>& sealing_m,
             std::vector<double>* ground_s = nullptr, const SupportHeights* supports = nullptr) const;

  /// Every sealing pixel as runs.
  const PixelRuns& runs() const { return runs_; }
  const RunAdapter& runAdapter() const { return adapter_; }

 private:
  PixelRuns runs_;
  RunAdapter adapter_;
};

}  // namespace climbsim::sealing
