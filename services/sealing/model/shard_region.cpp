#include "shard_region.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <utility>

namespace climbsim::sealing {

/// The region's pixels in the order of dist, with their graph and distances.
struct ShardRegion::Layout {
  SealingSubgraph graph;
  std::vector<double> dist_m;
  std::vector<std::size_t> band_end;
  double band_m = 0.0;
  double margin_m = 0.0;
};

ShardRegion::Layout ShardRegion::layoutOf(const StripMasks& masks, const std::vector<std::size_t>& own_segments,
                             double pixel_size_m) {
  const SealingSubgraph whole = wholeSealingGraph(masks);
  const std::size_t n = whole.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, inf);
  // Dijkstra from every own pixel at once; edge lengths s (orthogonal) and s sqrt 2 (diagonal).
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (const std::size_t s : own_segments) {
    if (s >= masks.segmentCount()) throw std::out_of_range("ShardRegion: no segment " + std::to_string(s));
    for (const std::uint32_t k : masks.segmentPixels(s)) {
      dist[k] = 0.0;
      queue.emplace(0.0, k);
    }
  }
  const double diagonal_m = pixel_size_m * std::sqrt(2.0);
  while (!queue.empty()) {
    const auto [d, k] = queue.top();
    queue.pop();
    if (d > dist[k]) continue;
    for (std::size_t j = 0; j < 8; ++j) {
      const std::int32_t m = whole.neighbours[8 * static_cast<std::size_t>(k) + j];
      if (m < 0) continue;
      const double next = d + (j < 4 ? pixel_size_m : diagonal_m);
      if (next < dist[m]) {
        dist[m] = next;
        queue.emplace(next, static_cast<std::uint32_t>(m));
      }
    }
  }
  std::vector<std::uint32_t> order;
  for (std::uint32_t k = 0; k < n; ++k) {
    if (dist[k] < inf) order.push_back(k);
  }
  const double band_m = kBandPixels * pixel_size_m;
  const auto bandOf = [&](std::uint32_t k) { return static_cast<std::size_t>(dist[k] / band_m); };
  // Ascending sealing index = raster order within a band.
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return bandOf(a) < bandOf(b); });
  std::vector<std::int32_t> local_of(n, -1);
  for (std::size_t i = 0; i < order.size(); ++i) local_of[order[i]] = static_cast<std::int32_t>(i);

  ShardRegion::Layout layout;
  layout.graph.sealing_index = order;
  layout.graph.neighbours.assign(8 * order.size(), -1);
  layout.band_m = band_m;
  for (std::size_t i = 0; i < order.size(); ++i) {
    layout.dist_m.push_back(dist[order[i]]);
    const std::size_t band = bandOf(order[i]);
    if (layout.band_end.size() <= band) layout.band_end.resize(band + 1, i);
    layout.band_end[band] = i + 1;
    for (std::size_t j = 0; j < 8; ++j) {
      const std::int32_t m = whole.neighbours[8 * static_cast<std::size_t>(order[i]) + j];
      if (m >= 0) layout.graph.neighbours[8 * i + j] = local_of[m];
    }
  }
  layout.margin_m = 2.0 * diagonal_m;
  return layout;
}

ShardRegion::ShardRegion(const StripMasks& masks, const Neighbourhood& /*nbh*/,
                         const std::vector<std::size_t>& own_segments, double pixel_size_m)
    : ShardRegion(masks, layoutOf(masks, own_segments, pixel_size_m)) {}

ShardRegion::ShardRegion(const StripMasks& masks, Layout layout)
    : masks_(masks),
      order_(std::move(layout.graph.sealing_index)),
      dist_m_(std::move(layout.dist_m)),
      band_end_(std::move(layout.band_end)),
      band_m_(layout.band_m),
      margin_m_(layout.margin_m) {
  band_of_pixel_.assign(masks.sealingPixels().size(), kNoBand);
  for (std::size_t b = 0, i = 0; b < band_end_.size(); ++b) {
    if (b + 1 >= kNoBand) throw std::length_error("ShardRegion: more than 65534 bands");
    for (; i < band_end_[b]; ++i) band_of_pixel_[order_[i]] = static_cast<std::uint16_t>(b);
  }
  runs_.resize(band_end_.size());
  for (const std::uint32_t k : order_) raster_.push_back(masks.sealingPixels()[k]);
  for (std::size_t i = 0; i < raster_.size(); ++i) {
    if (dist_m_[i] == 0.0) own_raster_.push_back(raster_[i]);
  }
}

const PixelRuns& ShardRegion::runs(std::size_t bands) const {
  bands = std::clamp<std::size_t>(bands, 1, band_end_.size());
  auto& slot = runs_[bands - 1];
  if (!slot) {
    const auto limit = static_cast<std::uint16_t>(bands);
    slot = std::make_unique<PixelRuns>(
        pixelRunsOf(masks_, [&](std::uint32_t k) { return band_of_pixel_[k] < limit; }));
  }
  return *slot;
}

std::size_t ShardRegion::bandsWithin(double reach_m) const {
  if (!(reach_m > 0.0)) return 0;
  if (!(reach_m < std::numeric_limits<double>::infinity())) return band_end_.size();
  const double bands = std::ceil(reach_m / band_m_);
  if (bands >= static_cast<double>(band_end_.size())) return band_end_.size();
  return static_cast<std::size_t>(bands);
}

std::size_t ShardRegion::countWithin(double reach_m) const {
  // Bands 0..b-1 cover [0, b band_m), so b = ceil(reach / band_m) bands hold dist < reach.
  return countOfBands(bandsWithin(reach_m));
}

std::size_t ShardRegion::staticCount(const SealingParams& params, double upper_bound_m) const {
  return countWithin((upper_bound_m + params.travel_m) / params.max_slope + margin_m_);
}

std::size_t ShardRegion::activeCount(const SealingParams& params, const std::vector<float>& ground_m,
                                     double upper_bound_m) const {
  return countOfBands(activeBands(params, ground_m, upper_bound_m));
}

std::size_t ShardRegion::activeBands(const SealingParams& params, const std::vector<float>& ground_m,
                                     double upper_bound_m) const {
  const std::size_t reachable_bands = bandsWithin((upper_bound_m + params.travel_m) / params.max_slope + margin_m_);
  if (upper_bound_m < std::numeric_limits<double>::infinity()) {
    // h_max <= U: the bound itself, no pass over the pixels (the adapter checks the ones it
    // reads). The h_max - h_min_own term only helps on walls without a crack; left out.
    const double reach_m = (upper_bound_m + params.travel_m) / params.max_slope + margin_m_;
    return std::max<std::size_t>(1, std::min(reachable_bands, bandsWithin(reach_m)));
  }
  const std::size_t reachable = countOfBands(reachable_bands);
  double h_max = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < reachable; ++i) {
    const float h = ground_m[raster_[i]];
    if (!std::isfinite(h)) throw std::invalid_argument("depth image: " + nonFinitePixel(masks_.grid(), raster_[i], h));
    h_max = std::max(h_max, static_cast<double>(h));
  }
  double h_min_own = std::numeric_limits<double>::infinity();
  for (const std::uint32_t raster : own_raster_) h_min_own = std::min(h_min_own, static_cast<double>(ground_m[raster]));
  const double reach_m = std::min(h_max + params.travel_m, h_max - h_min_own) / params.max_slope + margin_m_;
  return std::max<std::size_t>(1, std::min(reachable_bands, bandsWithin(reach_m)));
}

}  // namespace climbsim::sealing
