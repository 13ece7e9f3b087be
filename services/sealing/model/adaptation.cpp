#include "adaptation.hpp"

#include "cpu_avx.hpp"
#include "run_stretches.hpp"

#include <cmath>
#include <algorithm>
#include <cstring>
#include <type_traits>

#include <limits>
#include <stdexcept>
#include <utility>

namespace climbsim::sealing {

std::vector<double> adaptNaive(const StripMasks& masks, const Neighbourhood& nbh, const std::vector<float>& ground_m,
                               int* passes, const SupportHeights* supports) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  std::vector<double> height(pixels.size());
  for (std::size_t k = 0; k < pixels.size(); ++k) height[k] = ground_m[pixels[k]];
  if (supports != nullptr) {
    for (std::size_t i = 0; i < supports->raster.size(); ++i) {
      const std::int32_t k = masks.sealingIndexOfPixel(supports->raster[i]);
      if (k >= 0) height[k] = std::max(height[k], static_cast<double>(supports->height_m[i]));
    }
  }
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

namespace {

/// Flags fa[t] where a[t] raises b[t] by more than `step` [m], t < count. Branch-free along
/// consecutive memory, and inlined into the pass over the runs: their pairs come in short
/// stretches (a strip's width), where a call per stretch would cost more than its compares.
inline void flagRaisers(const double* __restrict a, const double* __restrict b, std::uint8_t* __restrict fa,
                        std::uint32_t count, double step) {
  for (std::uint32_t t = 0; t < count; ++t) fa[t] |= static_cast<std::uint8_t>(a[t] - step > b[t]);
}

/// Whether one of `count` neighbouring pairs (a[t], b[t]) has a member that raises the other
/// by more than `step` [m]: reads only, two pairs at a time in SSE2 registers where the CPU has
/// them (every x86-64), the same compares as flagRaisers. The last two pairs are read as one
/// more pair of lanes (a pair read twice changes no answer).
inline bool anyRaiser(const double* a, const double* b, std::uint32_t count, double step) {
  std::uint32_t t = 0;
  bool any = false;
#if defined(__SSE2__)
  if (count >= 2) {
    const __m128d s = _mm_set1_pd(step);
    const auto raises = [&](std::uint32_t at) {
      const __m128d x = _mm_loadu_pd(a + at);
      const __m128d y = _mm_loadu_pd(b + at);
      return _mm_or_pd(_mm_cmpgt_pd(_mm_sub_pd(x, s), y), _mm_cmpgt_pd(_mm_sub_pd(y, s), x));
    };
    __m128d acc = _mm_setzero_pd();
    for (; t < count; t += 2) acc = _mm_or_pd(acc, raises(t + 2 <= count ? t : count - 2));
    return _mm_movemask_pd(acc) != 0;
  }
#endif
  for (; t < count; ++t) any = any || a[t] - step > b[t] || b[t] - step > a[t];
  return any;
}

/// Flags both members of `count` neighbouring pairs (a[t], b[t]) where one raises the other
/// (fa and fb may overlap, as along a run: one pass each). Most stretches of a frame hold no
/// raiser: they are only read (anyRaiser).
inline void seedPairs(const double* a, const double* b, std::uint8_t* fa, std::uint8_t* fb, std::uint32_t count,
                      double step) {
  if (!anyRaiser(a, b, count, step)) return;
  flagRaisers(a, b, fa, count, step);
  flagRaisers(b, a, fb, count, step);
}

/// Flags the seeds among the pixels of `runs`: those that raise a neighbour by more than its
/// step as the values h stand, pair by pair along the runs (left-right, orth_m [m]) and along
/// the vertical pairs (every unordered pair once; diag_m [m] for the diagonal ones).
void seedRaisers(const PixelRuns& runs, double* h, std::uint8_t* f, double orth_m, double diag_m) {
  for (const PixelRuns::Run& run : runs.runs) {
    seedPairs(h + run.first, h + run.first + 1, f + run.first, f + run.first + 1, run.count - 1, orth_m);
  }
  for (const PixelRuns::VerticalPairs& pair : runs.pairs) {
    seedPairs(h + pair.upper, h + pair.lower, f + pair.upper, f + pair.lower, pair.count,
              pair.diagonal != 0 ? diag_m : orth_m);
  }
}

#if defined(CLIMBSIM_SEALING_AVX)
/// anyRaiser four pairs at a time in AVX registers: the same compares (ordered: NaN raises
/// nothing). The last four pairs are read as one more block when `count` is no multiple of 4.
__attribute__((target("avx"))) inline bool anyRaiserAvx(const double* a, const double* b, std::uint32_t count,
                                                        double step) {
  if (count < 4) return anyRaiser(a, b, count, step);
  const __m256d s = _mm256_set1_pd(step);
  __m256d acc = _mm256_setzero_pd();
  for (std::uint32_t t = 0; t < count; t += 4) {
    const std::uint32_t at = t + 4 <= count ? t : count - 4;
    const __m256d x = _mm256_loadu_pd(a + at);
    const __m256d y = _mm256_loadu_pd(b + at);
    acc = _mm256_or_pd(acc, _mm256_or_pd(_mm256_cmp_pd(_mm256_sub_pd(x, s), y, _CMP_GT_OQ),
                                         _mm256_cmp_pd(_mm256_sub_pd(y, s), x, _CMP_GT_OQ)));
  }
  return _mm256_movemask_pd(acc) != 0;
}

/// seedPairs with anyRaiserAvx: the same flags.
__attribute__((target("avx"))) inline void seedPairsAvx(double* h, std::uint8_t* f, std::uint32_t a, std::uint32_t b,
                                                        std::uint32_t count, double step) {
  if (!anyRaiserAvx(h + a, h + b, count, step)) return;
  flagRaisers(h + a, h + b, f + a, count, step);
  flagRaisers(h + b, h + a, f + b, count, step);
}

/// seedRaisers with seedPairsAvx: the same flags.
__attribute__((target("avx"))) void seedRaisersAvx(const PixelRuns& runs, double* h, std::uint8_t* f, double orth_m,
                                                   double diag_m) {
  for (const PixelRuns::Run& run : runs.runs) seedPairsAvx(h, f, run.first, run.first + 1, run.count - 1, orth_m);
  for (const PixelRuns::VerticalPairs& pair : runs.pairs) {
    seedPairsAvx(h, f, pair.upper, pair.lower, pair.count, pair.diagonal != 0 ? diag_m : orth_m);
  }
}

#endif

/// Raises the start values h[k] of the pixels of `supports` that lie in `runs` (ascending
/// sealing index, as the supports' raster indices map to) to their support heights, and `top`
/// to the highest start value.
void raiseToSupports(const StripMasks& masks, const SupportHeights& supports, const PixelRuns& runs, double* h,
                     double& top) {
  auto run = runs.runs.begin();
  for (std::size_t i = 0; i < supports.raster.size() && run != runs.runs.end(); ++i) {
    const std::int32_t k = masks.sealingIndexOfPixel(supports.raster[i]);
    if (k < 0) continue;
    const auto index = static_cast<std::uint32_t>(k);
    while (run != runs.runs.end() && run->first + run->count <= index) ++run;
    if (run == runs.runs.end() || run->first > index) continue;
    const auto v = static_cast<double>(supports.height_m[i]);
    if (v > h[index]) h[index] = v;
    top = std::max(top, h[index]);
  }
}

}  // namespace

RunAdapter::RunAdapter(const StripMasks& masks, const Neighbourhood& nbh) : masks_(&masks), links_(masks), nbh_(nbh) {}

void RunAdapter::adapt(const std::vector<float>& ground_m, const PixelRuns& runs, double floor_m,
                       std::vector<double>& height, std::vector<double>* ground_s,
                       const SupportHeights* supports) const {
  if (height.size() < links_.size()) height.resize(links_.size());
  if (ground_s != nullptr && ground_s->size() < links_.size()) ground_s->resize(links_.size());
  if (runs.pixels == 0) return;
  double* const h = height.data();
  double* const gs = ground_s != nullptr ? ground_s->data() : nullptr;
  auto& flag = scratch_.flag;
  if (flag.size() < links_.size()) flag.assign(links_.size(), 0);
  std::uint8_t* const f = flag.data();

  // Start values along the runs: max(h_g, floor), flags cleared. Four partial maxima and
  // minima so that the loop is not one long chain of dependent max operations.
  const double inf = std::numeric_limits<double>::infinity();
  double top4[4] = {-inf, -inf, -inf, -inf};
  double bottom4[4] = {inf, inf, inf, inf};
  bool finite = true;
#if defined(__SSE2__)
  // Four values at a time in SSE2 registers: maxpd (minpd) takes its first operand where it
  // compares greater (less), the same choices as the scalar lines; |v| <= FLT_MAX is
  // std::isfinite (NaN compares false).
  const __m128d floor2 = _mm_set1_pd(floor_m);
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 max_finite = _mm_set1_ps(std::numeric_limits<float>::max());
  __m128 finite4 = _mm_castsi128_ps(_mm_set1_epi32(-1));
  __m128d top2[2] = {_mm_set1_pd(-inf), _mm_set1_pd(-inf)};
  __m128d bottom2[2] = {_mm_set1_pd(inf), _mm_set1_pd(inf)};
#endif
  const auto startRuns = [&](auto keepGround) {
    for (const PixelRuns::Run& run : runs.runs) {
      const float* __restrict g = ground_m.data() + run.raster;
      double* __restrict out = h + run.first;
      double* __restrict ground_out = decltype(keepGround)::value ? gs + run.first : nullptr;
      const std::uint32_t count = run.count;
      std::uint32_t t = 0;
#if defined(__SSE2__)
      for (; t + 4 <= count; t += 4) {
        const __m128 x = _mm_loadu_ps(g + t);
        finite4 = _mm_and_ps(finite4, _mm_cmple_ps(_mm_and_ps(x, abs_mask), max_finite));
        const __m128d v[2] = {_mm_cvtps_pd(x), _mm_cvtps_pd(_mm_movehl_ps(x, x))};
        for (int u = 0; u < 2; ++u) {
          const __m128d start = _mm_max_pd(v[u], floor2);
          _mm_storeu_pd(out + t + 2 * u, start);
          if constexpr (decltype(keepGround)::value) _mm_storeu_pd(ground_out + t + 2 * u, v[u]);
          top2[u] = _mm_max_pd(start, top2[u]);
          bottom2[u] = _mm_min_pd(start, bottom2[u]);
        }
      }
#else
      for (; t + 4 <= count; t += 4) {
        for (int u = 0; u < 4; ++u) {
          const float v = g[t + u];
          finite &= std::isfinite(v);
          const double start = static_cast<double>(v) > floor_m ? static_cast<double>(v) : floor_m;
          out[t + u] = start;
          if constexpr (decltype(keepGround)::value) ground_out[t + u] = static_cast<double>(v);
          top4[u] = start > top4[u] ? start : top4[u];
          bottom4[u] = start < bottom4[u] ? start : bottom4[u];
        }
      }
#endif
      for (; t < count; ++t) {
        const float v = g[t];
        finite &= std::isfinite(v);
        const double start = static_cast<double>(v) > floor_m ? static_cast<double>(v) : floor_m;
        out[t] = start;
        if constexpr (decltype(keepGround)::value) ground_out[t] = static_cast<double>(v);
        top4[0] = start > top4[0] ? start : top4[0];
        bottom4[0] = start < bottom4[0] ? start : bottom4[0];
      }
    }
  };
  forEachStretch(runs, [f](std::uint32_t first, std::uint32_t end) { std::memset(f + first, 0, end - first); });
  if (gs != nullptr) {
    startRuns(std::true_type{});
  } else {
    startRuns(std::false_type{});
  }
#if defined(__SSE2__)
  finite = finite && _mm_movemask_ps(finite4) == 0xF;
  for (int u = 0; u < 2; ++u) {
    double lanes[2];
    _mm_storeu_pd(lanes, top2[u]);
    top4[2 * u] = std::max(top4[2 * u], lanes[0]);
    top4[2 * u + 1] = std::max(top4[2 * u + 1], lanes[1]);
    _mm_storeu_pd(lanes, bottom2[u]);
    bottom4[2 * u] = std::min(bottom4[2 * u], lanes[0]);
    bottom4[2 * u + 1] = std::min(bottom4[2 * u + 1], lanes[1]);
  }
#endif
  double top_m = std::max(std::max(top4[0], top4[1]), std::max(top4[2], top4[3]));
  const double bottom_m = std::min(std::min(bottom4[0], bottom4[1]), std::min(bottom4[2], bottom4[3]));
  if (!finite) {
    for (const PixelRuns::Run& run : runs.runs) {
      for (std::uint32_t t = 0; t < run.count; ++t) {
        if (!std::isfinite(ground_m[run.raster + t])) throw NonFiniteGround(run.raster + t, ground_m[run.raster + t]);
      }
    }
  }

  // A support only raises a start value: the lowest start stays a lower bound of every value.
  if (supports != nullptr && !supports->empty()) raiseToSupports(*masks_, *supports, runs, h, top_m);

  // Seeds: pixels that raise a neighbour as the ground stands (seedRaisers). A pixel that
  // raises nobody now can only start to once it is raised itself (its neighbours only go up),
  // and then it is queued.
  const double orth_m = nbh_.step_m[0];
  const double diag_m = nbh_.step_m[4];
#if defined(CLIMBSIM_SEALING_AVX)
  if (cpuHasAvx()) {
    seedRaisersAvx(runs, h, f, orth_m, diag_m);
  } else {
    seedRaisers(runs, h, f, orth_m, diag_m);
  }
#else
  seedRaisers(runs, h, f, orth_m, diag_m);
#endif

  // Dial's bucket queue: buckets one orthogonal step wide, highest heights first. A pixel
  // raises others by at least one step, so never into a bucket already emptied (rounding
  // may put it in the current one, which is emptied until it stays empty).
  const double width_m = orth_m;
  const auto bucketOf = [&](double v) { return static_cast<std::size_t>((top_m - v) / width_m); };
  auto& buckets = scratch_.buckets;
  const std::size_t last = bucketOf(bottom_m);
  buckets.resize(std::max(buckets.size(), last + 1));
  for (std::size_t b = 0; b <= last; ++b) buckets[b].clear();
  // Few pixels are seeds: their flags are found eight at a time.
  bool any = false;
  for (const PixelRuns::Run& run : runs.runs) {
    std::uint32_t k = run.first;
    const std::uint32_t end = run.first + run.count;
    for (; k + 8 <= end; k += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, f + k, sizeof word);
      if (word == 0) continue;
      for (std::uint32_t j = k; j < k + 8; ++j) {
        if (f[j] == 0) continue;
        f[j] = 0;  // from here on: 1 = done (its neighbours were relaxed with its current height)
        buckets[bucketOf(h[j])].push_back(j);
        any = true;
      }
    }
    for (; k < end; ++k) {
      if (f[k] == 0) continue;
      f[k] = 0;
      buckets[bucketOf(h[k])].push_back(k);
      any = true;
    }
  }
  if (!any) return;

  const std::uint32_t* up_first = links_.up_first.data();
  const std::uint32_t* down_first = links_.down_first.data();
  const std::uint8_t* mask = links_.mask.data();
  for (std::size_t b = 0; b <= last; ++b) {
    auto& bucket = buckets[b];
    // The oracle's update, with the roles of the pair swapped (the step is symmetric). A
    // neighbour outside the runs holds NaN: never raised.
    const auto relax = [&](std::uint32_t m, double raised) {
      if (raised > h[m]) {
        h[m] = raised;
        f[m] = 0;
        buckets[std::max(b, bucketOf(raised))].push_back(m);
      }
    };
    while (!bucket.empty()) {
      const std::uint32_t k = bucket.back();
      bucket.pop_back();
      if (f[k]) continue;  // queued more than once
      f[k] = 1;
      const double value = h[k];
      const double orth = value - orth_m;
      const double diag = value - diag_m;
      const unsigned bits = mask[k];
      if (bits & 1u) relax(k + 1, orth);
      if (bits & 4u) relax(k - 1, orth);
      // Row below: down-left (5), down (1), down-right (4) at consecutive indices.
      if (bits & (0x32u)) {
        std::uint32_t m = down_first[k];
        if (bits & 32u) relax(m++, diag);
        if (bits & 2u) relax(m++, orth);
        if (bits & 16u) relax(m, diag);
      }
      // Row above: up-left (7), up (3), up-right (6).
      if (bits & (0xC8u)) {
        std::uint32_t m = up_first[k];
        if (bits & 128u) relax(m++, diag);
        if (bits & 8u) relax(m++, orth);
        if (bits & 64u) relax(m, diag);
      }
    }
  }
}

SealingAdapter::SealingAdapter(const StripMasks& masks, const Neighbourhood& nbh)
    : runs_(pixelRunsOf(masks, [](std::uint32_t) { return true; })), adapter_(masks, nbh) {}

std::vector<double> SealingAdapter::adapt(const std::vector<float>& ground_m) const {
  std::vector<double> sealing_m;
  adapt(ground_m, sealing_m);
  return sealing_m;
}

void SealingAdapter::adapt(const std::vector<float>& ground_m, std::vector<double>& sealing_m) const {
  adapt(ground_m, -std::numeric_limits<double>::infinity(), sealing_m);
}

void SealingAdapter::adapt(const std::vector<float>& ground_m, double floor_m, std::vector<double>& sealing_m,
                           std::vector<double>* ground_s, const SupportHeights* supports) const {
  sealing_m.resize(runs_.pixels);
  adapter_.adapt(ground_m, runs_, floor_m, sealing_m, ground_s, supports);
}

}  // namespace climbsim::sealing
