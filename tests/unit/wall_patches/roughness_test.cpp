// Rough concrete: zero mean, the asked RMS and the asked correlation length, measured on
// the exported and re-imported mesh at random points, with tolerances from the number of
// independent samples.

#include <gtest/gtest.h>

#include <cmath>

#include "climbsim/wall_patches/mesh_io.hpp"
#include "climbsim/wall_patches/rough_surface.hpp"
#include "climbsim/wall_patches/seeded_random.hpp"
#include "surface_sampler.hpp"
#include "climbsim/wall_patches/wall_patch.hpp"

namespace climbsim::surface {
namespace {

struct RoughCase {
  double rms_m;
  double correlation_length_m;
  double grid_m;
};

class SurfaceRoughness : public ::testing::TestWithParam<RoughCase> {};

TEST_P(SurfaceRoughness, HasZeroMeanTheAskedRmsAndCorrelationLength) {
  const RoughCase c = GetParam();
  PatchSpec spec;
  spec.size_m = 2.0;
  spec.grid_m = c.grid_m;
  spec.seed = 42;
  spec.rough.rms_m = c.rms_m;
  spec.rough.correlation_length_m = c.correlation_length_m;
  const test::ScopedTempDir dir("rough");
  const std::string path = dir.path + "/rough.ply";
  writeMesh(path, generateWallPatch(spec).mesh);
  const SurfaceMesh mesh = readMesh(path);
  const test::SurfaceSampler sampler(mesh);

  // For the autocorrelation exp(-r^2/l^2) the field holds about N = A / (pi l^2 / 2)
  // independent samples: the mean's standard error is rms / sqrt(N), the RMS's relative one
  // 1 / sqrt(2 N), a correlation coefficient's about 1 / sqrt(N).
  const double l = c.correlation_length_m;
  const double area = (spec.size_m - 2 * l) * (spec.size_m - 2 * l);
  const double independent = area / (M_PI * l * l / 2.0);
  const int samples = 200000;
  SeededRandom random(99);
  const double lags[] = {0.5 * l, l, 2.0 * l};
  double sum = 0.0, square_sum = 0.0;
  double product_sum[3] = {0, 0, 0};
  for (int k = 0; k < samples; ++k) {
    const double x = random.uniform(l, spec.size_m - 3 * l), y = random.uniform(l, spec.size_m - l);
    const double z = *sampler.height(x, y);
    sum += z;
    square_sum += z * z;
    for (int j = 0; j < 3; ++j) product_sum[j] += z * *sampler.height(x + lags[j], y);
  }
  const double mean = sum / samples;
  const double rms = std::sqrt(square_sum / samples);
  EXPECT_NEAR(mean, 0.0, 4.0 * c.rms_m / std::sqrt(independent));
  // Linear interpolation between vertices lowers the RMS by about (h / l)^2 / 2 (< 3 % here).
  const double h = spec.grid_m;
  EXPECT_NEAR(rms, c.rms_m, c.rms_m * (4.0 / std::sqrt(2.0 * independent) + 0.5 * (h / l) * (h / l)));
  for (int j = 0; j < 3; ++j) {
    const double correlation = (product_sum[j] / samples) / (rms * rms);
    const double expected = std::exp(-(lags[j] * lags[j]) / (l * l));
    EXPECT_NEAR(correlation, expected, 4.0 / std::sqrt(independent) + (h / l) * (h / l)) << "lag " << lags[j];
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, SurfaceRoughness,
                         ::testing::Values(RoughCase{0.001, 0.02, 0.004}, RoughCase{0.0025, 0.04, 0.008},
                                           RoughCase{0.0005, 0.015, 0.003}));

TEST(SurfaceRoughGrid, IsExactlyNormalisedOnTheVertices) {
  const HeightGrid grid = roughHeights({0.002, 0.03}, 1.0, 200, 5);
  double sum = 0.0, square = 0.0;
  for (double z : grid.z_m) {
    sum += z;
    square += z * z;
  }
  const double n = static_cast<double>(grid.z_m.size());
  EXPECT_NEAR(sum / n, 0.0, 1e-15);
  EXPECT_NEAR(std::sqrt(square / n), 0.002, 1e-15);
}

TEST(SurfaceRoughGrid, ZeroRmsIsFlat) {
  const HeightGrid grid = roughHeights({0.0, 0.03}, 1.0, 50, 5);
  for (double z : grid.z_m) EXPECT_EQ(z, 0.0);
}

TEST(SurfaceSeededRandom, UniformAndNormalHaveTheirMoments) {
  SeededRandom random(1234);
  const int n = 400000;
  double u_sum = 0, u_sq = 0, g_sum = 0, g_sq = 0, g_4 = 0;
  for (int k = 0; k < n; ++k) {
    const double u = random.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    u_sum += u;
    u_sq += u * u;
    const double g = random.normal();
    g_sum += g;
    g_sq += g * g;
    g_4 += g * g * g * g;
  }
  // 5 standard errors: var(u) = 1/12, var(u^2) = 4/45, var(g^2) = 2, var(g^4) = 96.
  EXPECT_NEAR(u_sum / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(u_sq / n, 1.0 / 3, 5 * std::sqrt(4.0 / 45 / n));
  EXPECT_NEAR(g_sum / n, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(g_sq / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(g_4 / n, 3.0, 5 * std::sqrt(96.0 / n));
}

}  // namespace
}  // namespace climbsim::surface
