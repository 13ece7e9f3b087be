#include "climbsim/shard_tiles/shard_pixels.hpp"

#include <algorithm>

namespace climbsim::sealing {

ShardPixels::ShardPixels(const SealingParams& params, const StripMasks& masks)
    : params_(params), masks_(masks), nbh_(params.max_slope, masks.grid().pixel_size_m) {}

const ShardRegion& ShardPixels::region(const std::vector<std::size_t>& segments) const {
  auto& slot = regions_[segments];
  if (!slot) slot = std::make_unique<ShardRegion>(masks_, nbh_, segments, masks_.grid().pixel_size_m);
  return *slot;
}

std::size_t ShardPixels::neededCount(const std::vector<std::size_t>& segments, double upper_bound_m) const {
  if (segments.size() == masks_.segmentCount()) return masks_.sealingPixels().size();
  return region(segments).staticCount(params_, upper_bound_m);
}

std::vector<std::uint32_t> ShardPixels::neededPixels(const std::vector<std::size_t>& segments,
                                                     double upper_bound_m) const {
  const auto& pixels = masks_.sealingPixels();
  std::vector<std::uint32_t> out;
  if (segments.size() == masks_.segmentCount()) {
    out.assign(pixels.begin(), pixels.end());
  } else {
    const ShardRegion& part = region(segments);
    const std::size_t count = part.staticCount(params_, upper_bound_m);
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) out.push_back(pixels[part.sealingIndices()[i]]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

PixelBox ShardPixels::neededBox(const std::vector<std::size_t>& segments, double upper_bound_m) const {
  const PixelGrid& grid = masks_.grid();
  const int w = grid.width_px;
  int r_lo = grid.height_px, r_hi = -1, c_lo = w, c_hi = -1;
  for (const std::uint32_t raster : neededPixels(segments, upper_bound_m)) {
    const int r = static_cast<int>(raster / w);
    const int c = static_cast<int>(raster % w);
    r_lo = std::min(r_lo, r);
    r_hi = std::max(r_hi, r);
    c_lo = std::min(c_lo, c);
    c_hi = std::max(c_hi, c);
  }
  if (r_hi < 0) return {};
  return PixelBox{r_lo, c_lo, r_hi - r_lo + 1, c_hi - c_lo + 1};
}

}  // namespace climbsim::sealing
