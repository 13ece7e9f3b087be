#include "sealing_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace climbsim::sealing {

SealingModel::SealingModel(SealingParams params, const RobotGeometry& geometry, const PixelGrid& grid,
                           const std::string& source)
    : params_(std::move(params)),
      masks_(std::make_unique<StripMasks>(geometry, grid, source, params_.strip_outline)),
      nbh_(params_.max_slope, grid.pixel_size_m),
      adapter_(std::make_unique<SealingAdapter>(*masks_, nbh_)),
      shards_(params_, *masks_) {
  if (params_.channel_bound) edges_ = std::make_unique<StripEdges>(geometry, *masks_);
  if (params_.segment_names.size() != masks_->segmentCount() ||
      params_.segment_length_m.size() != masks_->segmentCount()) {
    throw std::invalid_argument("SealingModel: the parameters and the geometry disagree on the segments");
  }
}

void SealingModel::compute(const DepthGrid& depth, const std::vector<std::size_t>& segments,
                           SealingResult& out) const {
  computeLeaks(depth, segments, -std::numeric_limits<double>::infinity(), out);
}

void SealingModel::computeLeaks(const DepthGrid& depth, const std::vector<std::size_t>& segments, double none_at_m,
                                SealingResult& out) const {
  // Shape here; the values where they are read (a shard reads only its region).
  const std::string why = checkDepthGridShape(depth, grid());
  if (!why.empty()) throw std::invalid_argument("depth image: " + why);
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  try {
    adapt(depth, segments, out);
  } catch (const NonFiniteGround& e) {
    throw std::invalid_argument("depth image: " + nonFinitePixel(grid(), e.raster, e.value));
  }
  // The leakage of every segment asked for: each segment's share-weighted gaps summed over its
  // pixels in raster order, as segmentLeak does (the same doubles), and the shares whose ground
  // is at or below none_at_m, as step() defines them. The adaptation left h_g per sealing index
  // in ground_s_ (the same doubles as the image's floats). The counts over the travel and the
  // shares over no wall are 0 unless the gap pass saw such a pixel (then summed in order).
  sums_.assign(segmentCount(), LeakSums{});
  const double* h = out.sealing_m.data();
  const double* ground = ground_s_.data();
  const double travel_m = params_.travel_m;
  gap_s_.resize(out.sealing_m.size());
  const GapScan scan = scanGaps(*adapted_runs_, h, ground, travel_m, none_at_m, gap_s_.data());
  const auto leakPixelsOf = [&](std::size_t s) { return LeakPixels{&masks_->leakPixels(s), &masks_->leakShares(s)}; };
  const auto keep = [&](std::size_t s, const GapSum& sum) {
    sums_.at(s).sum_m = sum.sum_m;
    sums_.at(s).max_gap_m = sum.max_gap_m;
  };
  for (std::size_t i = 0; i < segments.size(); i += 2) {
    GapSum first, second;
    if (i + 1 < segments.size()) {
      sumGapsPair(leakPixelsOf(segments[i]), leakPixelsOf(segments[i + 1]), gap_s_.data(), first, second);
      keep(segments[i + 1], second);
    } else {
      sumGaps(leakPixelsOf(segments[i]), gap_s_.data(), first);
    }
    keep(segments[i], first);
  }
  for (const std::size_t s : segments) {
    if (!scan.any_over_travel && !scan.any_without_wall) break;
    const auto& pixels = masks_->leakPixels(s);
    const auto& shares = masks_->leakShares(s);
    std::size_t over = 0;
    double none = 0.0;
    for (std::size_t n = 0; n < pixels.size(); ++n) {
      over += h[pixels[n]] > travel_m ? 1 : 0;
      none += ground[pixels[n]] <= none_at_m ? shares[n] : 0.0;
    }
    sums_[s].over_travel_px = over;
    sums_[s].none = none;
  }
  out.segments.assign(segmentCount(), SegmentLeak{});
  for (const std::size_t s : segments) {
    const LeakSums& sum = sums_[s];
    SegmentLeak& leak = out.segments[s];
    leak.pixels = masks_->leakPixels(s).size();
    leak.max_gap_m = sum.max_gap_m;
    leak.over_travel_px = sum.over_travel_px;
    leak.mean_gap_m = sum.sum_m / masks_->shareSum(s);
    leak.leak_area_m2 = params_.segment_length_m[s] * (params_.basic_gap_m + params_.kappa_L * leak.mean_gap_m);
    leak.no_surface_share = sum.none / masks_->shareSum(s);
    if (edges_) {
      // L_i <= l_i L_basic + kappa_L min(A_side_a, A_side_b) (channel_bound.hpp).
      const double bound_m2 = params_.segment_length_m[s] * params_.basic_gap_m +
                              params_.kappa_L * edges_->channelArea_m2(*masks_, s, params_.segment_length_m[s], depth.height_m, out.sealing_m);
      leak.leak_area_m2 = std::min(leak.leak_area_m2, bound_m2);
    }
  }
}

void SealingModel::adapt(const DepthGrid& depth, const std::vector<std::size_t>& segments,
                         SealingResult& out) const {
  // The travel limit as the adaptation's floor: the same doubles as applyTravel afterwards.
  const double floor_m = -params_.travel_m;
  if (segments.size() == segmentCount()) {
    adapter_->adapt(depth.height_m, floor_m, out.sealing_m, &ground_s_, &depth.supports);
    adapted_runs_ = &adapter_->runs();
    out.adapted_px = out.sealing_m.size();
    out.filled_by = nullptr;
    out.filled_bands = 0;
    return;
  }
  const ShardRegion& part = region(segments);
  const std::size_t bands = part.activeBands(params_, depth.height_m, depth.upper_bound_m);
  const PixelRuns& runs = part.runs(bands);
  // NaN outside the region (the adapter leaves those pixels alone and takes NaN for "not in
  // the region"): all of it the first time, else only where the last frame's larger region
  // wrote.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = masks_->sealingPixels().size();
  if (out.filled_by != &part || out.sealing_m.size() != n) {
    out.sealing_m.assign(n, nan);
  } else if (out.filled_bands > bands) {
    // The region's pixels come band by band: those of the bands left out are one stretch.
    const auto& order = part.sealingIndices();
    const std::size_t end = part.countOfBands(out.filled_bands);
    for (std::size_t i = part.countOfBands(bands); i < end; ++i) out.sealing_m[order[i]] = nan;
  }
  adapter_->runAdapter().adapt(depth.height_m, runs, floor_m, out.sealing_m, &ground_s_, &depth.supports);
  adapted_runs_ = &runs;
  out.adapted_px = runs.pixels;
  out.filled_by = &part;
  out.filled_bands = bands;
}

const ShardRegion& SealingModel::region(const std::vector<std::size_t>& segments) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  return shards_.region(segments);
}

SealingState SealingModel::initialState(std::vector<std::size_t> segments) const {
  SealingState state;
  state.segments = std::move(segments);
  state.leaks = closedLeaks();
  return state;
}

SealingOutputs SealingModel::step(SealingState& state, const SealingInputs& inputs, std::int64_t t_ns,
                                  std::int64_t /*dt_ns: no dynamics inside a step*/) const {
  SealingOutputs out;
  if (inputs.depth != nullptr) {
    if (t_ns < state.t_ns) {
      throw std::invalid_argument("depth image of t_ns = " + std::to_string(t_ns) +
                                  " is older than the one whose leakage is in force (t_ns = " +
                                  std::to_string(state.t_ns) + ")");
    }
    // The scene writes far for a ray that meets nothing (and clamps deeper heights to it).
    computeLeaks(*inputs.depth, state.segments, inputs.far_m + 1e-6, state.last);
    state.t_ns = t_ns;
    for (const std::size_t s : state.segments) state.leaks[s] = state.last.segments[s];
    ++state.computed;
    out.computed = true;
  }
  out.leaks = state.leaks;
  return out;
}

SealingResult SealingModel::compute(const DepthGrid& depth) const {
  const std::string why = checkDepthGrid(depth, grid());
  if (!why.empty()) throw std::invalid_argument("depth image: " + why);
  std::vector<std::size_t> all(segmentCount());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  SealingResult out;
  compute(depth, all, out);
  return out;
}

std::size_t SealingModel::neededCount(const std::vector<std::size_t>& segments, double upper_bound_m) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  return shards_.neededCount(segments, upper_bound_m);
}

std::vector<std::uint32_t> SealingModel::neededPixels(const std::vector<std::size_t>& segments,
                                                      double upper_bound_m) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  return shards_.neededPixels(segments, upper_bound_m);
}

PixelBox SealingModel::neededBox(const std::vector<std::size_t>& segments, double upper_bound_m) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  return shards_.neededBox(segments, upper_bound_m);
}

std::vector<SegmentLeak> SealingModel::closedLeaks() const {
  std::vector<SegmentLeak> leaks;
  for (std::size_t s = 0; s < segmentCount(); ++s) leaks.push_back(closedSegmentLeak(params_, *masks_, s));
  return leaks;
}

}  // namespace climbsim::sealing
