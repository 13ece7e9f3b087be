#include "height_screen.hpp"

#include "cpu_avx.hpp"

#include <algorithm>
#include <limits>

namespace climbsim::sealing {
namespace {

#if defined(CLIMBSIM_SEALING_AVX)
/// The values v[0 .. 32 m - 1] (m whole blocks of 32, n rounded down) screened in AVX registers:
/// the same verdicts and maximum as the SSE2 loop. Returns the count screened.
__attribute__((target("avx"))) std::size_t screenAvx(const float* v, std::size_t n, float low_f, float high_f,
                                                     bool& ok, float& top) {
  const __m256 low = _mm256_set1_ps(low_f);
  const __m256 high = _mm256_set1_ps(high_f);
  __m256 top4[4], ok4[4];
  for (int j = 0; j < 4; ++j) {
    top4[j] = _mm256_set1_ps(top);
    ok4[j] = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  }
  std::size_t i = 0;
  for (; i + 32 <= n; i += 32) {
    for (int j = 0; j < 4; ++j) {
      const __m256 x = _mm256_loadu_ps(v + i + 8 * j);
      ok4[j] = _mm256_and_ps(ok4[j], _mm256_and_ps(_mm256_cmp_ps(x, low, _CMP_GE_OQ), _mm256_cmp_ps(x, high, _CMP_LE_OQ)));
      top4[j] = _mm256_max_ps(top4[j], x);
    }
  }
  const __m256 ok_all = _mm256_and_ps(_mm256_and_ps(ok4[0], ok4[1]), _mm256_and_ps(ok4[2], ok4[3]));
  ok = ok && _mm256_movemask_ps(ok_all) == 0xFF;
  const __m256 top_all = _mm256_max_ps(_mm256_max_ps(top4[0], top4[1]), _mm256_max_ps(top4[2], top4[3]));
  float lanes[8];
  _mm256_storeu_ps(lanes, top_all);
  for (const float lane : lanes) top = std::max(top, lane);
  return i;
}

#endif

}  // namespace

bool screenHeights(const float* v, std::size_t n, float low_f, float high_f, float& top) {
  std::size_t i = 0;
  bool ok = true;
  top = -std::numeric_limits<float>::infinity();
#if defined(CLIMBSIM_SEALING_AVX)
  if (cpuHasAvx()) i = screenAvx(v, n, low_f, high_f, ok, top);
#endif
#if defined(__SSE2__)
  const __m128 low = _mm_set1_ps(low_f);
  const __m128 high = _mm_set1_ps(high_f);
  __m128 top4[4], ok4[4];
  for (int j = 0; j < 4; ++j) {
    top4[j] = _mm_set1_ps(top);
    ok4[j] = _mm_castsi128_ps(_mm_set1_epi32(-1));
  }
  for (; i + 16 <= n; i += 16) {
    for (int j = 0; j < 4; ++j) {
      const __m128 x = _mm_loadu_ps(v + i + 4 * j);
      ok4[j] = _mm_and_ps(ok4[j], _mm_and_ps(_mm_cmpge_ps(x, low), _mm_cmple_ps(x, high)));
      top4[j] = _mm_max_ps(top4[j], x);
    }
  }
  const __m128 ok_all = _mm_and_ps(_mm_and_ps(ok4[0], ok4[1]), _mm_and_ps(ok4[2], ok4[3]));
  ok = ok && _mm_movemask_ps(ok_all) == 0xF;
  const __m128 top_all = _mm_max_ps(_mm_max_ps(top4[0], top4[1]), _mm_max_ps(top4[2], top4[3]));
  float lanes[4];
  _mm_storeu_ps(lanes, top_all);
  for (const float lane : lanes) top = std::max(top, lane);
#endif
  for (; i < n; ++i) {
    ok = ok && v[i] >= low_f && v[i] <= high_f;
    top = top < v[i] ? v[i] : top;
  }
  return ok;
}

}  // namespace climbsim::sealing
