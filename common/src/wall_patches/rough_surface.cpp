#include "climbsim/wall_patches/rough_surface.hpp"

#include <cmath>

#include "climbsim/wall_patches/seeded_random.hpp"

namespace climbsim::surface {

HeightGrid roughHeights(const Roughness& rough, double size_m, int cells, std::uint64_t seed) {
  HeightGrid grid;
  grid.cells = cells;
  grid.spacing_m = size_m / cells;
  const int n = cells + 1;
  grid.z_m.assign(static_cast<std::size_t>(n) * n, 0.0);
  if (rough.rms_m <= 0.0) return grid;

  const double sigma_cells = 0.5 * rough.correlation_length_m / grid.spacing_m;
  const int radius = sigma_cells > 0.0 ? static_cast<int>(std::ceil(3.0 * sigma_cells)) : 0;
  std::vector<double> kernel(2 * radius + 1, 1.0);
  for (int k = -radius; k <= radius; ++k)
    kernel[k + radius] = sigma_cells > 0.0 ? std::exp(-0.5 * (k * k) / (sigma_cells * sigma_cells)) : 1.0;

  const int padded = n + 2 * radius;
  SeededRandom random(seed);
  std::vector<double> noise(static_cast<std::size_t>(padded) * padded);
  for (double& value : noise) value = random.normal();

  // Rows first (only the rows needed by the column pass), then columns.
  std::vector<double> rows(static_cast<std::size_t>(padded) * n, 0.0);
  for (int y = 0; y < padded; ++y)
    for (int x = 0; x < n; ++x) {
      double sum = 0.0;
      const double* row = &noise[static_cast<std::size_t>(y) * padded + x];
      for (int k = 0; k <= 2 * radius; ++k) sum += kernel[k] * row[k];
      rows[static_cast<std::size_t>(y) * n + x] = sum;
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double sum = 0.0;
      for (int k = 0; k <= 2 * radius; ++k) sum += kernel[k] * rows[static_cast<std::size_t>(y + k) * n + x];
      grid.z_m[static_cast<std::size_t>(y) * n + x] = sum;
    }

  double mean = 0.0;
  for (double z : grid.z_m) mean += z;
  mean /= static_cast<double>(grid.z_m.size());
  double square_sum = 0.0;
  for (double& z : grid.z_m) {
    z -= mean;
    square_sum += z * z;
  }
  const double rms = std::sqrt(square_sum / static_cast<double>(grid.z_m.size()));
  if (rms > 0.0)
    for (double& z : grid.z_m) z *= rough.rms_m / rms;
  return grid;
}

}  // namespace climbsim::surface
