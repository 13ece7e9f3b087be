#pragma once
/// @file
/// The generator's random numbers: std::mt19937_64 with an explicit seed and our own
/// mappings to uniform and normal variates, so that a seed gives the same bytes on every
/// platform (the std::*_distribution algorithms are implementation-defined).

#include <cstdint>
#include <random>

namespace climbsim::surface {

/// splitmix64 of (seed, stream): independent seeds for the parts of one patch (roughness,
/// crack network) and for the blocks of a pylon, from one user seed.
std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream);

/// Seeded random stream.
class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1): the top 53 bits of one engine output times 2^-53.
  double uniform01();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Standard normal N(0, 1) by the Box–Muller transform (both values of a pair are used).
  double normal();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace climbsim::surface
