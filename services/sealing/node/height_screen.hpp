#pragma once
/// @file
/// The one pass over a depth image's heights before the sealing reads them (checkDepthImage).

#include <cstddef>

namespace climbsim::sealing {

/// Whether every one of v[0 .. n-1] lies in [low_f, high_f] (NaN does not), and in `top` the
/// largest of them (meaningful only then; a +0/-0 tie may come out as either zero). One pass
/// with independent running maxima and verdicts, 32 values at a time in AVX registers where the
/// CPU has them, else 16 in SSE2 registers (every x86-64); the maximum is the same value in any
/// order, and each verdict is one exact compare per value.
bool screenHeights(const float* v, std::size_t n, float low_f, float high_f, float& top);

}  // namespace climbsim::sealing
