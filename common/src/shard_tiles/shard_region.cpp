#include "climbsim/shard_tiles/shard_region.hpp"

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
  std::vector<ShardRegion::OwnPixel> own_by_depth;
  double band_m = 0.0;
  double diagonal_m = 0.0;
  double margin_m = 0.0;
};

namespace {

/// Path distance [m] of every sealing pixel of `whole` from the nearest pixel with
/// source[k] != 0 (Dijkstra; edges s orthogonal, s sqrt 2 diagonal); +inf if none is connected.
std::vector<double> distancesFrom(const SealingSubgraph& whole, const std::vector<char>& source, double pixel_size_m) {
  std::vector<double> dist(whole.size(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::uint32_t k = 0; k < whole.size(); ++k) {
    if (source[k] == 0) continue;
    dist[k] = 0.0;
    queue.emplace(0.0, k);
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
  return dist;
}

}  // namespace

ShardRegion::Layout ShardRegion::layoutOf(const StripMasks& masks, const std::vector<std::size_t>& own_segments,
                             double pixel_size_m) {
  const SealingSubgraph whole = wholeSealingGraph(masks);
  const std::size_t n = whole.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<char> own(n, 0);
  for (const std::size_t s : own_segments) {
    if (s >= masks.segmentCount()) throw std::out_of_range("ShardRegion: no segment " + std::to_string(s));
    // Every pixel the segment's leakage reads (also its neighbours' at junctions and outlines).
    for (const std::uint32_t k : masks.leakPixels(s)) own[k] = 1;
  }
  // dist from the own pixels; depth of every own pixel below the cut: its distance from the
  // nearest sealing pixel of another shard.
  const std::vector<double> dist = distancesFrom(whole, own, pixel_size_m);
  std::vector<char> others(n, 0);
  for (std::size_t k = 0; k < n; ++k) others[k] = own[k] == 0 && dist[k] < inf ? 1 : 0;
  const std::vector<double> depth = distancesFrom(whole, others, pixel_size_m);
  const double diagonal_m = pixel_size_m * std::sqrt(2.0);
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
  layout.diagonal_m = diagonal_m;
  layout.margin_m = 2.0 * diagonal_m;
  // Own pixels next to another shard's come first; those no other shard's pixel reaches are
  // left out (nothing from outside can reach them either).
  for (const std::uint32_t k : order) {
    if (own[k] != 0 && depth[k] < inf) layout.own_by_depth.push_back({masks.sealingPixels()[k], depth[k]});
  }
  const auto depthBand = [&](const OwnPixel& p) { return static_cast<std::size_t>(p.depth_m / band_m); };
  std::stable_sort(layout.own_by_depth.begin(), layout.own_by_depth.end(),
                   [&](const OwnPixel& a, const OwnPixel& b) { return depthBand(a) < depthBand(b); });
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
      own_by_depth_(std::move(layout.own_by_depth)),
      band_m_(layout.band_m),
      diagonal_m_(layout.diagonal_m),
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
  double h_max = upper_bound_m;
  double reach_m = (upper_bound_m + params.travel_m) / params.max_slope + margin_m_;
  if (!(upper_bound_m < std::numeric_limits<double>::infinity())) {
    // No bound: h_max and h_min_own from the pixels.
    const std::size_t reachable = countOfBands(reachable_bands);
    h_max = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < reachable; ++i) {
      const float h = ground_m[raster_[i]];
      if (!std::isfinite(h)) throw std::invalid_argument("depth image: " + nonFinitePixel(masks_.grid(), raster_[i], h));
      h_max = std::max(h_max, static_cast<double>(h));
    }
    double h_min_own = std::numeric_limits<double>::infinity();
    for (const std::uint32_t raster : own_raster_) h_min_own = std::min(h_min_own, static_cast<double>(ground_m[raster]));
    reach_m = std::min(h_max + params.travel_m, h_max - h_min_own) / params.max_slope + margin_m_;
  }
  // The own pixels' own floors (header): T >= (h_max - L(p)) / k - depth(p) + s sqrt 2 + margin
  // for every own pixel p, nearest the cut first; a pixel at depth e needs at most
  // (h_max + travel) / k - e + slack, so the walk stops where that no longer exceeds T.
  const double floor_m = -params.travel_m;
  const double slack_m = margin_m_ + diagonal_m_;
  double own_reach_m = 0.0;
  const double most_m = (h_max - floor_m) / params.max_slope + slack_m;
  for (const OwnPixel& p : own_by_depth_) {
    const double depth_floor_m = std::floor(p.depth_m / band_m_) * band_m_;
    if (most_m - depth_floor_m <= own_reach_m) break;
    const double ground = ground_m[p.raster];
    // A ground that is not finite: the adapter names it (every own pixel is adapted).
    const double lowest_m = std::isfinite(ground) ? std::max(ground, floor_m) : floor_m;
    own_reach_m = std::max(own_reach_m, (h_max - lowest_m) / params.max_slope - p.depth_m + slack_m);
    if (own_reach_m >= reach_m) break;
  }
  reach_m = std::min(reach_m, own_reach_m);
  return std::max<std::size_t>(1, std::min(reachable_bands, bandsWithin(reach_m)));
}

}  // namespace climbsim::sealing
