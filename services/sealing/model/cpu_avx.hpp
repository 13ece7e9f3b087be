#pragma once
/// @file
/// Whether the CPU runs AVX instructions: the sealing's passes over its pixels take four
/// doubles (eight floats) at a time where it does, else two (four) in SSE2 registers, with the
/// same compares and subtractions per value, so the same results. Includes the intrinsics both
/// need.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
/// The AVX passes are compiled (functions with __attribute__((target("avx")))).
#define CLIMBSIM_SEALING_AVX 1
#endif

namespace climbsim::sealing {

#if defined(CLIMBSIM_SEALING_AVX)

/// Whether the AVX passes may run where the CPU has AVX (true unless turned off, as the tests
/// do to compare both paths; set it before any pass runs, not while one does).
inline bool& avxPassesAllowed() {
  static bool allowed = true;
  return allowed;
}

/// Whether the AVX passes run: this CPU has AVX (asked once) and they are allowed.
inline bool cpuHasAvx() {
  static const bool avx = __builtin_cpu_supports("avx");
  return avx && avxPassesAllowed();
}
#endif

}  // namespace climbsim::sealing
