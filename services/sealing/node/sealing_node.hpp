#pragma once
/// @file
/// The sealing service without DDS: shard assignment, input checking and holding, and the
/// step of `climbsim-sealing`. main.cpp only moves samples in and out.
///
/// Sharding: shard i of N publishes the segments partitionSegments gives it (contiguous runs
/// by angle, about equal pixel counts). It adapts only the pixels that can influence them
/// (shard_region.hpp) and evaluates only its own segments (SealingModel::compute): its numbers
/// are the doubles that N = 1 gives, whatever N, and N shards together adapt little more than
/// the whole sealing once.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene.h"
#include "sealing.h"
#include "climbsim/shard_tiles/shard_partition.hpp"
#include "sealing_model.hpp"

namespace climbsim::sealing {

/// The sealing service's translation around SealingModel::step: picks the step's depth image
/// (checks it, passes over tiles for other shards), translates it to the model's input and the
/// output to Leakage, and names a segment over nothing once. The model's state lives here.
class SealingNode {
 public:
  using Model = SealingModel;  ///< the model it steps (model_contract.hpp)

  /// `model` must outlive the node.
  SealingNode(const SealingModel& model, const ShardSpec& shard);

  /// One due step: of the depth images given (one per producer), the last valid one that
  /// holds this shard's neededBox (and, for a masked tile, every pixel of its neededPixels) is
  /// computed (tiles for other shards are passed over); a bad
  /// one (checkDepthImage) is logged, counted and dropped. Without a valid image the last valid
  /// leakage is held (initially the closed sealing: l_i * L_basic). ConfigError naming the
  /// shard, its box and the tiles if valid tiles came but none holds the box (tiles for another
  /// shard count). Returns this shard's Leakage part (stamps left to the writer). Taken by
  /// value: the chosen whole image's pixels move into the node (pass an rvalue to avoid a copy).
  ///
  /// Each segment's no_surface_share is the share of its strip pixels at the image's far limit
  /// (no wall within reach). A segment whose share first reaches kNoSurfaceWarnShare is named
  /// in one warning with the image's time, its share and leak (once per segment and run): a
  /// seal hanging past the edge of the scene is not silently a huge leak.
  climbsim::Leakage step(std::vector<climbsim::DepthImage> depth_images);
  /// step(depth_images) in the lockstep's shape (t_ns, dt_ns, the samples of each input): the
  /// clock's time changes nothing, each image carries its own.
  climbsim::Leakage step(std::int64_t /*t_ns*/, std::int64_t /*dt_ns*/, std::vector<climbsim::DepthImage> depth_images) {
    return step(std::move(depth_images));
  }

  /// PNG bytes of the pictures of the last computed image, "edges" then "gaps"; empty before
  /// the first valid image.
  std::vector<std::pair<std::string, std::vector<unsigned char>>> pictures() const;

  const std::vector<std::size_t>& segments() const { return state_.segments; }
  /// The pixels this shard needs of an image none of whose heights exceeds height_bound_m [m]
  /// (a sample's heightBound_m: its camera's near plane, or less by its headroom).
  PixelBox neededBox(double height_bound_m) const;
  /// Leakage in force per segment, geometry order (only this shard's segments are meaningful).
  const std::vector<SegmentLeak>& leaks() const { return state_.leaks; }
  std::uint64_t dropped() const { return dropped_; }
  /// Sealing pixels adapted for the last computed image (this shard's region, or all).
  std::size_t lastAdaptedPixels() const { return state_.last.adapted_px; }
  std::uint64_t computed() const { return state_.computed; }
  /// Segments (geometry indices) named in a no-surface warning so far.
  const std::vector<std::size_t>& noSurfaceWarned() const { return no_surface_warned_; }

  /// Share of a segment's strip over nothing at which it is named in a warning.
  static constexpr double kNoSurfaceWarnShare = 0.1;
  /// "SEAL OVER NOTHING at t = T s: segment 'S' hangs over nothing (P % of its strip sees no
  /// wall); ..." for the first segment noSurfaceWarned() names, at the step of clock time t_ns:
  /// why a scenario with end_on.seal_over_nothing fails the run (the service and climbsim
  /// solo). "" while no segment is named.
  std::string sealOverNothingReason(std::int64_t t_ns) const;

 private:
  const SealingModel& model_;
  ShardSpec shard_;
  SealingState state_;
  std::optional<DepthGrid> last_depth_;
  bool last_is_tile_ = false;
  /// What the shard reads of an image whose heights are bounded (by near_m - headroom_m).
  struct Needed {
    PixelBox box;                       ///< SealingModel::neededBox
    std::vector<std::uint32_t> pixels;  ///< SealingModel::neededPixels
  };
  mutable std::map<std::size_t, Needed> needed_;  ///< by SealingModel::neededCount
  /// The last mask runs found to hold every pixel of *covering_need_ (a renderer sends the
  /// same runs for the same bound).
  mutable std::vector<std::uint32_t> covering_runs_;
  mutable const Needed* covering_need_ = nullptr;
  double last_far_m_ = -0.05;
  double last_near_m_ = 0.05;
  std::uint64_t dropped_ = 0;
  std::vector<std::size_t> no_surface_warned_;

  /// Names each segment whose no_surface_share first reaches kNoSurfaceWarnShare (see step).
  void warnNoSurface(std::int64_t t_ns);
  const Needed& needed(double height_bound_m) const;
  /// Whether a sample whose tile holds need.box (needed for its height bound) also holds every
  /// needed pixel: true without mask runs (or with malformed ones, which checkDepthImage
  /// names), else whether its runs cover need.pixels.
  bool holdsNeededPixels(const climbsim::DepthImage& sample, const Needed& need) const;
};

}  // namespace climbsim::sealing
