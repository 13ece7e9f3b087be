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
      masks_(std::make_unique<StripMasks>(geometry, grid, source)),
      nbh_(params_.max_slope, grid.pixel_size_m),
      adapter_(std::make_unique<SealingAdapter>(*masks_, nbh_)) {
  if (params_.channel_bound) edges_ = std::make_unique<StripEdges>(geometry, *masks_);
  if (params_.segment_names.size() != masks_->segmentCount() ||
      params_.segment_length_m.size() != masks_->segmentCount()) {
    throw std::invalid_argument("SealingModel: the parameters and the geometry disagree on the segments");
  }
}

void SealingModel::compute(const DepthGrid& depth, const std::vector<std::size_t>& segments,
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
  out.segments.assign(segmentCount(), SegmentLeak{});
  for (const std::size_t s : segments) {
    out.segments.at(s) = segmentLeak(params_, *masks_, s, depth.height_m, out.sealing_m);
    if (edges_) {
      // L_i <= l_i L_basic + kappa_L min(A_side_a, A_side_b) (channel_bound.hpp).
      SegmentLeak& leak = out.segments[s];
      const double bound_m2 = params_.segment_length_m[s] * params_.basic_gap_m +
                              params_.kappa_L * edges_->channelArea_m2(*masks_, s, params_.segment_length_m[s], depth.height_m, out.sealing_m);
      leak.leak_area_m2 = std::min(leak.leak_area_m2, bound_m2);
    }
  }
}

void SealingModel::adapt(const DepthGrid& depth, const std::vector<std::size_t>& segments, SealingResult& out) const {
  if (segments.size() == segmentCount()) {
    adapter_->adapt(depth.height_m, out.sealing_m);
    applyTravel(params_, out.sealing_m);
    out.adapted_px = out.sealing_m.size();
    out.filled_by = nullptr;
    return;
  }
  const ShardRegion& part = region(segments);
  const std::size_t active = part.activeCount(params_, depth.height_m, depth.upper_bound_m);
  part.adapter().adapt(depth.height_m, active, local_m_);
  applyTravel(params_, local_m_);
  // NaN outside the region: all of it the first time, else only where the last frame's
  // larger region wrote (same region object: same local order).
  const auto& index = part.sealingIndices();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (out.filled_by != &part || out.sealing_m.size() != masks_->sealingPixels().size()) {
    out.sealing_m.assign(masks_->sealingPixels().size(), nan);
    out.adapted_px = 0;
  }
  for (std::size_t i = active; i < out.adapted_px; ++i) out.sealing_m[index[i]] = nan;
  for (std::size_t i = 0; i < active; ++i) out.sealing_m[index[i]] = local_m_[i];
  out.adapted_px = active;
  out.filled_by = &part;
}

const ShardRegion& SealingModel::region(const std::vector<std::size_t>& segments) const {
  const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
  auto& slot = regions_[segments];
  if (!slot) slot = std::make_unique<ShardRegion>(*masks_, nbh_, segments, grid().pixel_size_m);
  return *slot;
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
    compute(*inputs.depth, state.segments, state.last);
    state.t_ns = t_ns;
    // The scene writes far for a ray that meets nothing (and clamps deeper heights to it).
    const double far_m = inputs.far_m + 1e-6;
    for (const std::size_t s : state.segments) {
      SegmentLeak& leak = state.leaks[s];
      leak = state.last.segments[s];
      const auto& pixels = masks_->segmentPixels(s);
      std::size_t none = 0;
      for (const std::uint32_t index : pixels) {
        none += static_cast<double>(inputs.depth->height_m[masks_->sealingPixels()[index]]) <= far_m ? 1 : 0;
      }
      leak.no_surface_share = pixels.empty() ? 0.0 : static_cast<double>(none) / static_cast<double>(pixels.size());
    }
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

PixelBox SealingModel::neededBox(const std::vector<std::size_t>& segments, double upper_bound_m) const {
  const auto& pixels = masks_->sealingPixels();
  const int w = grid().width_px;
  int r_lo = grid().height_px, r_hi = -1, c_lo = w, c_hi = -1;
  const auto include = [&](std::uint32_t raster) {
    const int r = static_cast<int>(raster / w);
    const int c = static_cast<int>(raster % w);
    r_lo = std::min(r_lo, r);
    r_hi = std::max(r_hi, r);
    c_lo = std::min(c_lo, c);
    c_hi = std::max(c_hi, c);
  };
  if (segments.size() == segmentCount()) {
    for (const std::uint32_t raster : pixels) include(raster);
  } else {
    const std::lock_guard<std::recursive_mutex> lock(cache_mutex_);
    const ShardRegion& part = region(segments);
    const std::size_t count = part.staticCount(params_, upper_bound_m);
    for (std::size_t i = 0; i < count; ++i) include(pixels[part.sealingIndices()[i]]);
  }
  if (r_hi < 0) return {};
  return PixelBox{r_lo, c_lo, r_hi - r_lo + 1, c_hi - c_lo + 1};
}

std::vector<SegmentLeak> SealingModel::closedLeaks() const {
  std::vector<SegmentLeak> leaks;
  for (std::size_t s = 0; s < segmentCount(); ++s) leaks.push_back(closedSegmentLeak(params_, *masks_, s));
  return leaks;
}

}  // namespace climbsim::sealing
