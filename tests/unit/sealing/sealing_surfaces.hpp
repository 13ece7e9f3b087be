#pragma once
/// @file
/// Synthetic wall surfaces under the robot for the sealing tests, benchmark and feeder:
/// rough concrete, straight cracks, holes, steps. Seeded (std::mt19937_64) with the mapping
/// to [0, 1) written out, so that every platform draws the same surfaces.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "climbsim/shard_tiles/depth_grid.hpp"

namespace climbsim::sealing::testing {

/// Uniform in [0, 1) from the top 53 bits.
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
inline double uniform(std::mt19937_64& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

/// A flat wall at `height_m` on `grid`.
inline DepthGrid flatWall(const PixelGrid& grid, float height_m = 0.0f) {
  DepthGrid depth;
  depth.grid = grid;
  depth.height_m.assign(grid.pixelCount(), height_m);
  return depth;
}

/// Adds roughness: bilinear interpolation of uniform values in ±amplitude_m on a lattice of
/// `cell_m`, plus white noise in ±noise_m per pixel.
inline void addRoughness(DepthGrid& d, std::mt19937_64& rng, double amplitude_m, double cell_m, double noise_m) {
  const PixelGrid& g = d.grid;
  const double extent_x = g.width_px * g.pixel_size_m;
  const double extent_y = g.height_px * g.pixel_size_m;
  const int nx = static_cast<int>(std::ceil(extent_x / cell_m)) + 2;
  const int ny = static_cast<int>(std::ceil(extent_y / cell_m)) + 2;
  std::vector<double> lattice(static_cast<std::size_t>(nx) * ny);
  for (double& v : lattice) v = uniform(rng, -amplitude_m, amplitude_m);
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      const double u = (g.xOfColumn_m(c) + extent_x / 2) / cell_m;
      const double v = (extent_y / 2 - g.yOfRow_m(r)) / cell_m;
      const int i = static_cast<int>(u);
      const int j = static_cast<int>(v);
      const double fu = u - i;
      const double fv = v - j;
      auto at = [&](int a, int b) { return lattice[static_cast<std::size_t>(b) * nx + a]; };
      const double smooth = (1 - fu) * (1 - fv) * at(i, j) + fu * (1 - fv) * at(i + 1, j) +
                            (1 - fu) * fv * at(i, j + 1) + fu * fv * at(i + 1, j + 1);
      d.height_m[static_cast<std::size_t>(r) * g.width_px + c] +=
          static_cast<float>(smooth + uniform(rng, -noise_m, noise_m));
    }
  }
}

/// A straight crack through the point (x_m, y_m) along angle_rad (R frame): flat bottom
/// `depth_m` below the surface across `bottom_width_m`, walls of `wall_slope` (m/m; <= 0 for
/// vertical walls); only where the coordinate along the crack is within ±half_length_m.
/// The crack cuts into the surface: h <- min(h, profile).
struct Crack {
  double x_m = 0.0;
  double y_m = 0.0;
  double angle_rad = 0.0;
  double bottom_width_m = 0.01;
  double depth_m = 0.01;
  double wall_slope = 0.0;
  double half_length_m = 1e9;

  /// Height of the crack profile at (x, y): 0 outside, -depth_m on the bottom [m].
  double profile_m(double x, double y) const {
    const double dx = x - x_m;
    const double dy = y - y_m;
    const double along = dx * std::cos(angle_rad) + dy * std::sin(angle_rad);
    const double across = std::abs(-dx * std::sin(angle_rad) + dy * std::cos(angle_rad));
    if (std::abs(along) > half_length_m) return 0.0;
    const double half_bottom = bottom_width_m / 2;
    if (across <= half_bottom) return -depth_m;
    if (wall_slope <= 0.0) return 0.0;
    return std::min(0.0, -depth_m + wall_slope * (across - half_bottom));
  }
};

inline void addCrack(DepthGrid& d, const Crack& crack) {
  const PixelGrid& g = d.grid;
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      float& h = d.height_m[static_cast<std::size_t>(r) * g.width_px + c];
      h = std::min(h, static_cast<float>(crack.profile_m(g.xOfColumn_m(c), g.yOfRow_m(r))));
    }
  }
}

/// A round hole (vertical walls) of `radius_m` and `depth_m` below the surface at (x, y).
inline void addHole(DepthGrid& d, double x_m, double y_m, double radius_m, double depth_m) {
  const PixelGrid& g = d.grid;
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      if (std::hypot(g.xOfColumn_m(c) - x_m, g.yOfRow_m(r) - y_m) <= radius_m) {
        float& h = d.height_m[static_cast<std::size_t>(r) * g.width_px + c];
        h = std::min(h, static_cast<float>(-depth_m));
      }
    }
  }
}

/// A step: the wall on the left of the line through (x, y) along angle_rad is `rise_m` higher.
inline void addStep(DepthGrid& d, double x_m, double y_m, double angle_rad, double rise_m) {
  const PixelGrid& g = d.grid;
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 0; c < g.width_px; ++c) {
      const double left = -(g.xOfColumn_m(c) - x_m) * std::sin(angle_rad) + (g.yOfRow_m(r) - y_m) * std::cos(angle_rad);
      if (left > 0) d.height_m[static_cast<std::size_t>(r) * g.width_px + c] += static_cast<float>(rise_m);
    }
  }
}

/// Clamps every height to [far_m, near_m] as the depth camera does.
inline void clampToCamera(DepthGrid& d, double far_m = -0.05, double near_m = 0.05) {
  for (float& h : d.height_m) h = std::clamp(h, static_cast<float>(far_m), static_cast<float>(near_m));
}

/// A random test surface: roughness, 1..3 cracks (random widths, depths 0..40 mm, vertical or
/// sloped walls), 0..3 holes, maybe a step; clamped to ±0.05 m.
inline DepthGrid randomSurface(const PixelGrid& grid, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  DepthGrid d = flatWall(grid);
  addRoughness(d, rng, uniform(rng, 0.0, 0.004), uniform(rng, 0.01, 0.1), uniform(rng, 0.0, 0.002));
  const int cracks = 1 + static_cast<int>(uniform01(rng) * 3);
  for (int k = 0; k < cracks; ++k) {
    Crack c;
    c.x_m = uniform(rng, -0.3, 0.3);
    c.y_m = uniform(rng, -0.3, 0.3);
    c.angle_rad = uniform(rng, 0.0, 3.14159265358979);
    c.bottom_width_m = uniform(rng, 0.002, 0.05);
    c.depth_m = uniform(rng, 0.0, 0.04);
    c.wall_slope = uniform01(rng) < 0.5 ? 0.0 : uniform(rng, 0.05, 2.0);
    c.half_length_m = uniform01(rng) < 0.5 ? 1e9 : uniform(rng, 0.05, 0.4);
    addCrack(d, c);
  }
  const int holes = static_cast<int>(uniform01(rng) * 4);
  for (int k = 0; k < holes; ++k) {
    addHole(d, uniform(rng, -0.35, 0.35), uniform(rng, -0.35, 0.35), uniform(rng, 0.003, 0.04),
            uniform(rng, 0.0, 0.06));
  }
  if (uniform01(rng) < 0.3) {
    addStep(d, uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3), uniform(rng, 0.0, 6.28), uniform(rng, -0.02, 0.02));
  }
  clampToCamera(d);
  return d;
}

/// Support heights (DepthGrid::supports) at about `share` of the pixels whose row neighbours
/// differ by more than 2 mm (a crack's, a hole's or a step's edge), each up to 4 mm above its
/// pixel (as the scene gives them: above the pixel's mean, at most the highest of the wall
/// within a pixel); upper_bound_m keeps bounding every height.
inline void addSupports(DepthGrid& d, std::uint64_t seed, double share = 0.7) {
  std::mt19937_64 rng(seed);
  const PixelGrid& g = d.grid;
  d.supports = SupportHeights{};
  for (int r = 0; r < g.height_px; ++r) {
    for (int c = 1; c + 1 < g.width_px; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * g.width_px + c;
      const float h = d.height_m[i];
      const float top = std::max(d.height_m[i - 1], d.height_m[i + 1]);
      if (top - h <= 0.002f || uniform01(rng) >= share) continue;
      d.supports.raster.push_back(static_cast<std::uint32_t>(i));
      d.supports.height_m.push_back(h + static_cast<float>(uniform(rng, 0.0, std::min(0.004, double(top - h)))));
    }
  }
  if (std::isfinite(d.upper_bound_m)) {
    for (const float v : d.supports.height_m) d.upper_bound_m = std::max(d.upper_bound_m, static_cast<double>(v));
  }
}

}  // namespace climbsim::sealing::testing
