#pragma once
/// @file
/// Rough concrete as Gaussian-filtered white noise on the vertex grid of the structured face.

#include <cstdint>
#include <vector>

#include "climbsim/wall_patches/patch_spec.hpp"

namespace climbsim::surface {

/// Heights on the (cells + 1) x (cells + 1) vertices of a square grid of spacing spacing_m:
/// vertex (i, j) sits at x = i spacing_m, y = j spacing_m (patch frame), index j (cells + 1) + i.
struct HeightGrid {
  int cells = 0;
  double spacing_m = 0.0;
  std::vector<double> z_m;
  double at(int i, int j) const { return z_m[static_cast<std::size_t>(j) * (cells + 1) + i]; }
};

/// White noise N(0, 1) on a grid padded by the kernel radius, filtered with the separable
/// kernel g(r) = exp(-r^2 / (2 sigma^2)), sigma = l / 2, so that the autocorrelation is
/// exp(-r^2 / l^2) (l = correlation_length_m); then shifted and scaled so that the grid's
/// mean is 0 and its RMS is exactly rms_m. rms_m = 0 gives zeros.
HeightGrid roughHeights(const Roughness& rough, double size_m, int cells, std::uint64_t seed);

}  // namespace climbsim::surface
