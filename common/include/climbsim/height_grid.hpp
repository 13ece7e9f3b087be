#pragma once
/// @file
/// The depth image reduced for the browser: block means of the wall heights, so that a
/// 256 x 256 float image (256 KiB) becomes a 64 x 64 grid of a few kB of JSON.

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

namespace climbsim {

/// Heights on a square grid centred on the robot, robot frame R (row 0 at +y, column 0 at -x,
/// as the depth image).
struct HeightGrid {
  int size = 0;                     ///< cells per side
  double cell_m = 0.0;              ///< edge of a cell on the wall [m]
  std::vector<float> height_m;      ///< size * size heights above the sealing plane [m]
};

/// Mean of each `block` x `block` pixels of a `width` x `height` image of `pixel_m` pixels.
/// Throws std::invalid_argument if the image is not square, `block` < 1 or does not divide it,
/// or `heights` has not width * height values.
HeightGrid downsampleHeights(const std::vector<float>& heights, std::uint32_t width, std::uint32_t height,
                             double pixel_m, int block);

/// The block size that gives at most `max_cells` cells per side (the smallest divisor of
/// `width` that does).
int blockFor(std::uint32_t width, int max_cells);

/// {"type": "depth", "step", "t_s", "size", "cell_m", "heights_mm": [...]} with heights in mm
/// rounded to 0.01 mm (the page needs no more; it keeps the message small).
nlohmann::json heightGridJson(const HeightGrid& grid, std::uint64_t step, std::int64_t t_ns);

}  // namespace climbsim
