#include "adaptation.hpp"

#include <cmath>
#include <queue>
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

SealingAdapter::SealingAdapter(const StripMasks& masks, const Neighbourhood& nbh) : masks_(masks), nbh_(nbh) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  neighbours_.assign(pixels.size() * 8, -1);
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const int r = static_cast<int>(pixels[k] / g.width_px);
    const int c = static_cast<int>(pixels[k] % g.width_px);
    for (std::size_t j = 0; j < 8; ++j) {
      const int nr = r + Neighbourhood::kOffsets[j][0];
      const int nc = c + Neighbourhood::kOffsets[j][1];
      if (nr < 0 || nr >= g.height_px || nc < 0 || nc >= g.width_px) continue;
      neighbours_[8 * k + j] = masks.sealingIndexOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
    }
  }
}

std::vector<double> SealingAdapter::adapt(const std::vector<float>& ground_m) const {
  std::vector<double> sealing_m;
  adapt(ground_m, sealing_m);
  return sealing_m;
}

void SealingAdapter::adapt(const std::vector<float>& ground_m, std::vector<double>& height) const {
  const auto& pixels = masks_.sealingPixels();
  const std::size_t n = pixels.size();
  height.resize(n);
  for (std::size_t k = 0; k < n; ++k) height[k] = ground_m[pixels[k]];

  // Seeds: pixels that raise a neighbour as the ground stands. Every unordered pair is looked
  // at once (offsets 0, 1, 4, 5 point forward). A pixel that raises nobody now can only start
  // to once it is raised itself (its neighbours only go up), and then it is queued.
  using Entry = std::pair<double, std::uint32_t>;
  std::vector<Entry> seeds;
  static constexpr std::size_t kForward[4] = {0, 1, 4, 5};
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t* nb = &neighbours_[8 * k];
    for (const std::size_t j : kForward) {
      const std::int32_t m = nb[j];
      if (m < 0) continue;
      const double step = nbh_.step_m[j];
      if (height[k] - step > height[m]) {
        seeds.emplace_back(height[k], static_cast<std::uint32_t>(k));
      } else if (height[m] - step > height[k]) {
        seeds.emplace_back(height[m], static_cast<std::uint32_t>(m));
      }
    }
  }
  if (seeds.empty()) return;

  std::priority_queue<Entry> queue(std::less<Entry>(), std::move(seeds));
  std::vector<std::uint8_t> done(n, 0);
  while (!queue.empty()) {
    const auto [value, k] = queue.top();
    queue.pop();
    // Stale entries: the pixel was raised after being queued, or already relaxed. A popped
    // pixel is final: later pops are no higher, and fl(v - step) <= v cannot raise it.
    if (done[k] || value != height[k]) continue;
    done[k] = 1;
    const std::int32_t* nb = &neighbours_[8 * static_cast<std::size_t>(k)];
    for (std::size_t j = 0; j < 8; ++j) {
      const std::int32_t m = nb[j];
      if (m < 0) continue;
      // The oracle's update, with the roles of the pair swapped: step is symmetric.
      const double raised = value - nbh_.step_m[j];
      if (raised > height[m]) {
        height[m] = raised;
        queue.emplace(raised, static_cast<std::uint32_t>(m));
      }
    }
  }
}

}  // namespace climbsim::sealing
