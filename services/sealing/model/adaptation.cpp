#include "adaptation.hpp"

#include <cmath>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace climbsim::sealing {

Neighbourhood::Neighbourhood(double max_slope, double pixel_size_m) {
  if (!(max_slope > 0.0) || !(pixel_size_m > 0.0)) {
    throw std::invalid_argument("Neighbourhood: max_slope and pixel_size_m must be > 0");
  }
  for (std::size_t j = 0; j < kOffsets.size(); ++j) {
    step_m[j] = j < 4 ? max_slope * pixel_size_m : max_slope * pixel_size_m * std::sqrt(2.0);
  }
}

std::vector<double> adaptNaive(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<float>& ground_m,
                               int* passes) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  std::vector<double> height(pixels.size());
  for (std::size_t k = 0; k < pixels.size(); ++k) height[k] = ground_m[pixels[k]];
  int count = 0;
  bool changed = true;
  while (changed) {
    changed = false;
    ++count;
    const std::vector<double> previous = height;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
      const int r = static_cast<int>(pixels[k] / g.width_px);
      const int c = static_cast<int>(pixels[k] % g.width_px);
      for (std::size_t j = 0; j < Neighbourhood::kOffsets.size(); ++j) {
        const int nr = r + Neighbourhood::kOffsets[j][0];
        const int nc = c + Neighbourhood::kOffsets[j][1];
        if (nr < 0 || nr >= g.height_px || nc < 0 || nc >= g.width_px) continue;
        const std::int32_t n = masks.sealingIndexOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
        if (n < 0) continue;
        const double raised = previous[n] - nbh.step_m[j];
        if (raised > height[k]) {
          height[k] = raised;
          changed = true;
        }
      }
    }
  }
  if (passes != nullptr) *passes = count;
  return height;
}

SealingSubgraph wholeSealingGraph(const StripMasks& masks) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  SealingSubgraph graph;
  graph.sealing_index.resize(pixels.size());
  graph.neighbours.assign(pixels.size() * 8, -1);
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    graph.sealing_index[k] = static_cast<std::uint32_t>(k);
    const int r = static_cast<int>(pixels[k] / g.width_px);
    const int c = static_cast<int>(pixels[k] % g.width_px);
    for (std::size_t j = 0; j < 8; ++j) {
      const int nr = r + Neighbourhood::kOffsets[j][0];
      const int nc = c + Neighbourhood::kOffsets[j][1];
      if (nr < 0 || nr >= g.height_px || nc < 0 || nc >= g.width_px) continue;
      graph.neighbours[8 * k + j] = masks.sealingIndexOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
    }
  }
  return graph;
}

SubgraphAdapter::SubgraphAdapter(SealingSubgraph graph, const StripMasks& masks, const Neighbourhood& nbh)
    : graph_(std::move(graph)), nbh_(nbh) {
  if (graph_.neighbours.size() != 8 * graph_.sealing_index.size()) {
    throw std::invalid_argument("SubgraphAdapter: 8 neighbour entries per pixel expected");
  }
  raster_of_.reserve(graph_.size());
  for (const std::uint32_t k : graph_.sealing_index) raster_of_.push_back(masks.sealingPixels().at(k));
}

void SubgraphAdapter::adapt(const std::vector<float>& ground_m, std::size_t active, std::vector<double>& height) const {
  const std::size_t n = std::min(active, graph_.size());
  height.resize(n);
  if (n == 0) return;
  const auto& raster = raster_of_;
  double top_m = -std::numeric_limits<double>::infinity();
  double bottom_m = std::numeric_limits<double>::infinity();
  bool finite = true;
  for (std::size_t k = 0; k < n; ++k) {
    const float h = ground_m[raster[k]];
    finite &= std::isfinite(h);
    height[k] = h;
    top_m = std::max(top_m, height[k]);
    bottom_m = std::min(bottom_m, height[k]);
  }
  if (!finite) {
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(ground_m[raster[k]])) throw NonFiniteGround(raster[k], ground_m[raster[k]]);
    }
  }
  // A neighbour exists for this call when its local index is below n (-1 wraps to the top).
  const auto exists = [n](std::int32_t m) { return static_cast<std::uint32_t>(m) < n; };

  // Dial's bucket queue: buckets one orthogonal step wide, highest heights first. A pixel
  // raises others by at least one step, so never into a bucket already emptied (rounding
  // may put it in the current one, which is emptied until it stays empty).
  const double width_m = nbh_.step_m[0];
  const auto bucketOf = [&](double h) { return static_cast<std::size_t>((top_m - h) / width_m); };
  auto& buckets = scratch_.buckets;
  buckets.resize(std::max(buckets.size(), bucketOf(bottom_m) + 1));
  for (auto& bucket : buckets) bucket.clear();

  // Seeds: pixels that raise a neighbour as the ground stands. Every unordered pair is looked
  // at once (offsets 0, 1, 4, 5 point forward). A pixel that raises nobody now can only start
  // to once it is raised itself (its neighbours only go up), and then it is queued.
  bool any = false;
  static constexpr std::size_t kForward[4] = {0, 1, 4, 5};
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t* nb = &graph_.neighbours[8 * k];
    for (const std::size_t j : kForward) {
      const std::int32_t m = nb[j];
      if (!exists(m)) continue;
      const double step = nbh_.step_m[j];
      if (height[k] - step > height[m]) {
        buckets[bucketOf(height[k])].push_back(static_cast<std::uint32_t>(k));
        any = true;
      } else if (height[m] - step > height[k]) {
        buckets[bucketOf(height[m])].push_back(static_cast<std::uint32_t>(m));
        any = true;
      }
    }
  }
  if (!any) return;

  // done[k]: k's neighbours were relaxed with its current height.
  auto& done = scratch_.done;
  done.assign(n, 0);
  const std::size_t last = bucketOf(bottom_m);
  for (std::size_t b = 0; b <= last; ++b) {
    auto& bucket = buckets[b];
    while (!bucket.empty()) {
      const std::uint32_t k = bucket.back();
      bucket.pop_back();
      if (done[k]) continue;  // queued more than once
      done[k] = 1;
      const double value = height[k];
      const std::int32_t* nb = &graph_.neighbours[8 * static_cast<std::size_t>(k)];
      for (std::size_t j = 0; j < 8; ++j) {
        const std::int32_t m = nb[j];
        if (!exists(m)) continue;
        // The oracle's update, with the roles of the pair swapped: step is symmetric.
        const double raised = value - nbh_.step_m[j];
        if (raised > height[m]) {
          height[m] = raised;
          done[m] = 0;
          buckets[std::max(b, bucketOf(raised))].push_back(static_cast<std::uint32_t>(m));
        }
      }
    }
  }
}

SealingAdapter::SealingAdapter(const StripMasks& masks, const Neighbourhood& nbh)
    : whole_(wholeSealingGraph(masks), masks, nbh) {}

std::vector<double> SealingAdapter::adapt(const std::vector<float>& ground_m) const {
  std::vector<double> sealing_m;
  adapt(ground_m, sealing_m);
  return sealing_m;
}

void SealingAdapter::adapt(const std::vector<float>& ground_m, std::vector<double>& sealing_m) const {
  whole_.adapt(ground_m, whole_.graph().size(), sealing_m);
}

}  // namespace climbsim::sealing
