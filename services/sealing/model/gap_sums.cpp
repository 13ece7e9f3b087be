#include "gap_sums.hpp"

#include "cpu_avx.hpp"
#include "run_stretches.hpp"

#include <algorithm>

namespace climbsim::sealing {
namespace {

/// Adds pixels [from, to) of one segment to its sums (the loop of segmentLeak).
inline void addGaps(const std::uint32_t* pixels, const double* shares, std::size_t from, std::size_t to,
                    const double* gap_m, GapSum& sum) {
  double sum_m = sum.sum_m;
  double max_gap_m = sum.max_gap_m;
  for (std::size_t n = from; n < to; ++n) {
    const double gap = gap_m[pixels[n]];
    sum_m += shares[n] * gap;
    max_gap_m = std::max(max_gap_m, gap);
  }
  sum.sum_m = sum_m;
  sum.max_gap_m = max_gap_m;
}

#if defined(CLIMBSIM_SEALING_AVX)
/// The gaps of k = first .. first + 4 m - 1 (whole blocks of four before end) in AVX registers,
/// the same subtractions and ordered compares as the loop of scanGaps; returns the next k.
__attribute__((target("avx"))) std::uint32_t scanGapsAvx(std::uint32_t first, std::uint32_t end,
                                                         const double* sealing_m, const double* ground_m,
                                                         double travel_m, double none_at_m, double* gap_m,
                                                         GapScan& scan) {
  const __m256d travel = _mm256_set1_pd(travel_m);
  const __m256d none_at = _mm256_set1_pd(none_at_m);
  __m256d over = _mm256_setzero_pd();
  __m256d without = _mm256_setzero_pd();
  std::uint32_t k = first;
  for (; k + 4 <= end; k += 4) {
    const __m256d h = _mm256_loadu_pd(sealing_m + k);
    const __m256d g = _mm256_loadu_pd(ground_m + k);
    _mm256_storeu_pd(gap_m + k, _mm256_sub_pd(h, g));
    over = _mm256_or_pd(over, _mm256_cmp_pd(h, travel, _CMP_GT_OQ));
    without = _mm256_or_pd(without, _mm256_cmp_pd(g, none_at, _CMP_LE_OQ));
  }
  scan.any_over_travel = scan.any_over_travel || _mm256_movemask_pd(over) != 0;
  scan.any_without_wall = scan.any_without_wall || _mm256_movemask_pd(without) != 0;
  return k;
}

#endif

}  // namespace

GapScan scanGaps(const PixelRuns& runs, const double* sealing_m, const double* ground_m, double travel_m,
                 double none_at_m, double* gap_m) {
  GapScan scan;
#if defined(CLIMBSIM_SEALING_AVX)
  const bool avx = cpuHasAvx();
#endif
  bool over = false;
  bool without = false;
#if defined(__SSE2__)
  const __m128d travel = _mm_set1_pd(travel_m);
  const __m128d none_at = _mm_set1_pd(none_at_m);
  __m128d over2 = _mm_setzero_pd();
  __m128d without2 = _mm_setzero_pd();
#endif
  // Along stretches of consecutive sealing indices, four values at a time in AVX registers
  // where the CPU has them, else two in SSE2 registers (every x86-64).
  forEachStretch(runs, [&](std::uint32_t first, std::uint32_t end) {
    std::uint32_t k = first;
#if defined(CLIMBSIM_SEALING_AVX)
    if (avx) k = scanGapsAvx(first, end, sealing_m, ground_m, travel_m, none_at_m, gap_m, scan);
#endif
#if defined(__SSE2__)
    for (; k + 2 <= end; k += 2) {
      const __m128d h = _mm_loadu_pd(sealing_m + k);
      const __m128d g = _mm_loadu_pd(ground_m + k);
      _mm_storeu_pd(gap_m + k, _mm_sub_pd(h, g));
      over2 = _mm_or_pd(over2, _mm_cmpgt_pd(h, travel));
      without2 = _mm_or_pd(without2, _mm_cmple_pd(g, none_at));
    }
#endif
    for (; k < end; ++k) {
      gap_m[k] = sealing_m[k] - ground_m[k];
      over = over || sealing_m[k] > travel_m;
      without = without || ground_m[k] <= none_at_m;
    }
  });
#if defined(__SSE2__)
  over = over || _mm_movemask_pd(over2) != 0;
  without = without || _mm_movemask_pd(without2) != 0;
#endif
  scan.any_over_travel = scan.any_over_travel || over;
  scan.any_without_wall = scan.any_without_wall || without;
  return scan;
}

void sumGapsPair(const LeakPixels& a, const LeakPixels& b, const double* gap_m, GapSum& sum_a, GapSum& sum_b) {
  const std::uint32_t* pa = a.pixels->data();
  const std::uint32_t* pb = b.pixels->data();
  const double* sa = a.shares->data();
  const double* sb = b.shares->data();
  const std::size_t both = std::min(a.pixels->size(), b.pixels->size());
  double sum_am = sum_a.sum_m, max_am = sum_a.max_gap_m;
  double sum_bm = sum_b.sum_m, max_bm = sum_b.max_gap_m;
  for (std::size_t n = 0; n < both; ++n) {
    const double gap_a = gap_m[pa[n]];
    const double gap_b = gap_m[pb[n]];
    sum_am += sa[n] * gap_a;
    sum_bm += sb[n] * gap_b;
    max_am = std::max(max_am, gap_a);
    max_bm = std::max(max_bm, gap_b);
  }
  sum_a = GapSum{sum_am, max_am};
  sum_b = GapSum{sum_bm, max_bm};
  addGaps(pa, sa, both, a.pixels->size(), gap_m, sum_a);
  addGaps(pb, sb, both, b.pixels->size(), gap_m, sum_b);
}

void sumGaps(const LeakPixels& a, const double* gap_m, GapSum& sum) {
  addGaps(a.pixels->data(), a.shares->data(), 0, a.pixels->size(), gap_m, sum);
}

}  // namespace climbsim::sealing
