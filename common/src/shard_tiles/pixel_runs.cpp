#include "climbsim/shard_tiles/pixel_runs.hpp"

#include <algorithm>

namespace climbsim::sealing {

PixelRuns pixelRunsByKey(const StripMasks& masks, const std::function<int(std::uint32_t)>& key, std::vector<int>& keys) {
  const auto& pixels = masks.sealingPixels();
  const auto w = static_cast<std::uint32_t>(masks.grid().width_px);
  PixelRuns out;
  keys.clear();
  for (std::uint32_t k = 0; k < pixels.size(); ++k) {
    const int kk = key(k);
    if (kk < 0) continue;
    if (!out.runs.empty()) {
      PixelRuns::Run& last = out.runs.back();
      // Next column of the same row, next sealing index, same key: the run goes on.
      if (last.first + last.count == k && last.raster + last.count == pixels[k] && pixels[k] % w != 0 &&
          keys.back() == kk) {
        ++last.count;
        ++out.pixels;
        continue;
      }
    }
    out.runs.push_back({k, 1, pixels[k]});
    keys.push_back(kk);
    ++out.pixels;
  }
  return out;
}

PixelRuns pixelRunsOf(const StripMasks& masks, const std::function<bool(std::uint32_t)>& member) {
  const auto w = static_cast<std::uint32_t>(masks.grid().width_px);
  std::vector<int> keys;
  PixelRuns out = pixelRunsByKey(masks, [&](std::uint32_t k) { return member(k) ? 0 : -1; }, keys);
  // Pairs between the runs of consecutive rows (a row holds a few runs: quadratic is fine).
  std::size_t row_begin = 0;
  while (row_begin < out.runs.size()) {
    const std::uint32_t row = out.runs[row_begin].raster / w;
    std::size_t row_end = row_begin;
    while (row_end < out.runs.size() && out.runs[row_end].raster / w == row) ++row_end;
    std::size_t next_end = row_end;
    while (next_end < out.runs.size() && out.runs[next_end].raster / w == row + 1) ++next_end;
    for (std::size_t a = row_begin; a < row_end; ++a) {
      const auto& A = out.runs[a];
      const auto a0 = static_cast<std::int64_t>(A.raster % w);
      const std::int64_t a1 = a0 + A.count;
      for (std::size_t b = row_end; b < next_end; ++b) {
        const auto& B = out.runs[b];
        const auto b0 = static_cast<std::int64_t>(B.raster % w);
        const std::int64_t b1 = b0 + B.count;
        for (const std::int64_t d : {0, -1, 1}) {
          // Columns c of A whose c + d lies in B.
          const std::int64_t lo = std::max(a0, b0 - d);
          const std::int64_t hi = std::min(a1, b1 - d);
          if (hi <= lo) continue;
          out.pairs.push_back({static_cast<std::uint32_t>(A.first + (lo - a0)),
                               static_cast<std::uint32_t>(B.first + (lo + d - b0)), static_cast<std::uint32_t>(hi - lo),
                               d != 0 ? 1u : 0u});
        }
      }
    }
    row_begin = row_end;
  }
  return out;
}

NeighbourLinks::NeighbourLinks(const StripMasks& masks) {
  const auto& pixels = masks.sealingPixels();
  const PixelGrid& g = masks.grid();
  const std::size_t n = pixels.size();
  up_first.assign(n, 0);
  down_first.assign(n, 0);
  mask.assign(n, 0);
  const auto indexAt = [&](int r, int c) -> std::int32_t {
    if (r < 0 || r >= g.height_px || c < 0 || c >= g.width_px) return -1;
    return masks.sealingIndexOfPixel(static_cast<std::size_t>(r) * g.width_px + c);
  };
  for (std::size_t k = 0; k < n; ++k) {
    const int r = static_cast<int>(pixels[k] / g.width_px);
    const int c = static_cast<int>(pixels[k] % g.width_px);
    std::uint8_t bits = 0;
    // kOffsets order: (0,1) (1,0) (0,-1) (-1,0) (1,1) (1,-1) (-1,1) (-1,-1).
    const int dr[8] = {0, 1, 0, -1, 1, 1, -1, -1};
    const int dc[8] = {1, 0, -1, 0, 1, -1, 1, -1};
    for (int j = 0; j < 8; ++j) {
      if (indexAt(r + dr[j], c + dc[j]) >= 0) bits = static_cast<std::uint8_t>(bits | (1u << j));
    }
    mask[k] = bits;
    for (const int side : {-1, 1}) {
      std::uint32_t first = 0;
      for (int dcol = -1; dcol <= 1; ++dcol) {
        const std::int32_t m = indexAt(r + side, c + dcol);
        if (m >= 0) {
          first = static_cast<std::uint32_t>(m);
          break;
        }
      }
      (side < 0 ? up_first : down_first)[k] = first;
    }
  }
}

}  // namespace climbsim::sealing
