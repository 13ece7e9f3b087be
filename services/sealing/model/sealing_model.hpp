#pragma once
/// @file
/// The sealing model of docs/design.md#sealing-and-leakage for one robot and one depth camera:
/// depth image in, sealing heights and leakage per segment out.
///
/// Sharding: the adaptation couples the segments (the strips are one continuous sealing and
/// a raise propagates across junctions), so a segment's leakage depends on its neighbours'
/// pixels, but only on those within a bounded path distance (shard_region.hpp). compute()
/// for a subset of the segments adapts only that subset's region for the frame and evaluates
/// the leakage formula for the segments asked for; each segment's numbers are the same doubles
/// whichever other segments are asked for.

#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <memory>
#include <string>
#include <vector>

#include "adaptation.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "channel_bound.hpp"
#include "gap_sums.hpp"
#include "leakage.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"
#include "climbsim/shard_tiles/shard_pixels.hpp"
#include "climbsim/shard_tiles/shard_region.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"
#include "climbsim/model_contract.hpp"

namespace climbsim::sealing {

/// What compute() gives for one depth image.
struct SealingResult {
  /// h_s after the travel limit, per sealing index (StripMasks::sealingPixels order) [m].
  /// When only some segments were computed, pixels outside the frame's region hold NaN.
  std::vector<double> sealing_m;
  /// Sealing pixels adapted for this result (all of them for every segment).
  std::size_t adapted_px = 0;
  /// The region that filled sealing_m (nullptr: the whole sealing) and how many of its bands;
  /// lets the next frame of the same shard reset only what changes.
  const ShardRegion* filled_by = nullptr;
  std::size_t filled_bands = 0;
  /// Per segment in geometry order; only the computed segments are filled (the others keep
  /// pixels = 0 and zeros).
  std::vector<SegmentLeak> segments;
};

/// What evolves between depth images (the contract's State): the leakage in force and the last
/// computed image's sealing. SealingModel::initialState makes it, step() advances it.
struct SealingState {
  /// The segments this state evaluates (geometry indices, ascending): all of them, or a shard's.
  std::vector<std::size_t> segments;
  /// Leakage in force per segment, geometry order (only `segments` are meaningful): a
  /// zero-order hold between images, initially the closed sealing (l_i * L_basic).
  std::vector<SegmentLeak> leaks;
  /// The last computed image's result: its sealing heights (pictures), and the region that
  /// filled them, so that the next image of the same shard resets only what changes.
  SealingResult last;
  std::uint64_t computed = 0;  ///< images computed so far
  /// Clock time of the image whose leakage is in force [ns] (-1: none yet, the closed
  /// sealing): step() refuses an older image, so a late sample never replaces a newer one.
  std::int64_t t_ns = -1;
};

/// One step's input: the depth image to compute, if one is due and valid.
struct SealingInputs {
  /// The step's depth image, values checked (checkDepthGrid, or a shard's region of them);
  /// nullptr: none this step, the leakage in force is held.
  const DepthGrid* depth = nullptr;
  /// Its camera's far limit [m] (heights of pixels that see no wall within reach).
  double far_m = -0.05;
};

/// One step's output.
struct SealingOutputs {
  /// Leakage in force per segment (SealingState::leaks after the step).
  std::vector<SegmentLeak> leaks;
  bool computed = false;  ///< a new image was computed (else the leakage was held)
};

/// The sealing as a model of the one contract (Params: SealingParams, the geometry and the
/// pixel grid given to the constructor; SealingState, SealingInputs, SealingOutputs, and
/// `Outputs step(State&, const Inputs&, t_ns, dt_ns)`). Everything that evolves is in the
/// caller's SealingState; the model keeps only caches that never change a result (each
/// shard's region, built on first use, and the adapter's work storage). Thread-safe: those
/// caches are used under a lock, so one model may serve several states on several threads
/// (the calls are serialised; each state's results are those it would get alone).
class SealingModel {
 public:
  /// The model contract's types (climbsim/model_contract.hpp).
  using Params = SealingParams;
  using State = SealingState;
  using Inputs = SealingInputs;
  using Outputs = SealingOutputs;

  /// Rasterises the strips of `geometry` into `grid`; throws ConfigError naming `source`
  /// (the robot file) if they do not fit (StripMasks).
  SealingModel(SealingParams params, const RobotGeometry& geometry, const PixelGrid& grid, const std::string& source);

  /// Adapts the sealing to `depth` and evaluates the segments `segments` (distinct indices in
  /// geometry order). std::invalid_argument with checkDepthGrid's reason for a wrong shape or
  /// a non-finite value among the pixels it reads (all sealing pixels, or a shard's region).
  /// Not reentrant (the adapter keeps its queue storage): one model per thread.
  void compute(const DepthGrid& depth, const std::vector<std::size_t>& segments, SealingResult& out) const;
  /// Every segment, after checking every pixel of `depth` (checkDepthGrid).
  SealingResult compute(const DepthGrid& depth) const;

  /// The pixels compute(depth, segments, ...) can read of an image whose heights are at most
  /// `upper_bound_m` [m] (the camera's near plane: of any image): the bounding box of the
  /// region's static part (shard_region.hpp), of every sealing pixel for all segments. A tile
  /// of the image that contains this box is all a shard needs.
  PixelBox neededBox(const std::vector<std::size_t>& segments, double upper_bound_m) const;
  /// The pixels themselves whose box neededBox is, as raster indices (row * W + col), ascending:
  /// what a masked tile for the shard must hold (`climbsim-scene --tile` renders and sends them).
  std::vector<std::uint32_t> neededPixels(const std::vector<std::size_t>& segments, double upper_bound_m) const;
  /// How many pixels neededPixels gives (whole bands of the region: bounds that give the same
  /// count give the same pixels), without listing them.
  std::size_t neededCount(const std::vector<std::size_t>& segments, double upper_bound_m) const;

  /// The leakage of a flat wall (l_i * L_basic) for every segment, geometry order.
  std::vector<SegmentLeak> closedLeaks() const;

  /// The state before the first image for `segments` (distinct, ascending geometry indices):
  /// the closed sealing's leakage.
  SealingState initialState(std::vector<std::size_t> segments) const;
  /// Computes inputs.depth, the image of clock time t_ns [ns], for the state's segments
  /// (compute) and puts their leakage in force, with each one's no_surface_share (the share of
  /// its strip pixels at or below far_m + 1 µm: no wall within reach), and state.t_ns = t_ns;
  /// without an image the leakage in force is held (a zero-order hold). The sealing has no
  /// dynamics inside a step, so dt_ns is not used: the leakage of an image holds until the
  /// next. std::invalid_argument as compute, and for an image older than the one in force
  /// (t_ns < state.t_ns), whose leakage would replace a newer one.
  SealingOutputs step(SealingState& state, const SealingInputs& inputs, std::int64_t t_ns, std::int64_t dt_ns) const;

  const SealingParams& params() const { return params_; }
  const StripMasks& masks() const { return *masks_; }
  const PixelGrid& grid() const { return masks_->grid(); }
  const Neighbourhood& neighbourhood() const { return nbh_; }
  std::size_t segmentCount() const { return params_.segment_names.size(); }

 private:
  SealingParams params_;
  std::unique_ptr<StripMasks> masks_;  ///< stable address: the adapter refers to it
  std::unique_ptr<StripEdges> edges_;  ///< only with SealingParams::channel_bound
  Neighbourhood nbh_;
  std::unique_ptr<SealingAdapter> adapter_;
  /// The region of each subset of segments asked for so far (built on first use), and the
  /// pixels each needs (as the scene's tiles for the shards compute them).
  ShardPixels shards_;
  /// Per-segment sums of one frame's leakage pass (kept: a frame allocates nothing).
  struct LeakSums {
    double sum_m = 0.0;
    double max_gap_m = 0.0;
    std::size_t over_travel_px = 0;
    double none = 0.0;  ///< sum of the shares over no wall (computeLeaks)
  };
  mutable std::vector<LeakSums> sums_;
  /// h_g per sealing index of the last adapted pixels, as the adaptation read them.
  mutable std::vector<double> ground_s_;
  /// h_s - h_g per sealing index of the last adapted pixels (computeLeaks).
  mutable std::vector<double> gap_s_;
  /// The pixels the last adapt() adapted (the whole sealing's runs, or a region's).
  mutable const PixelRuns* adapted_runs_ = nullptr;
  /// Guards the caches above and the adapters' work storage (compute, neededBox, region).
  mutable std::recursive_mutex cache_mutex_;

  /// h_s after the travel limit into out.sealing_m (the whole sealing or the region of
  /// `segments`); NonFiniteGround for a non-finite pixel read.
  void adapt(const DepthGrid& depth, const std::vector<std::size_t>& segments, SealingResult& out) const;
  /// compute(), and each segment's no_surface_share: the share of its strip pixels whose ground
  /// is at or below none_at_m [m] (-inf: none, 0).
  void computeLeaks(const DepthGrid& depth, const std::vector<std::size_t>& segments, double none_at_m,
                    SealingResult& out) const;

 public:
  /// The region compute() adapts for `segments` (built on first use; must not be all of them).
  const ShardRegion& region(const std::vector<std::size_t>& segments) const;
};

static_assert(is_model_v<SealingModel>, "SealingModel keeps the model contract");

}  // namespace climbsim::sealing
