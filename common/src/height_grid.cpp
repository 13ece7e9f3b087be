#include "climbsim/height_grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace climbsim {

HeightGrid downsampleHeights(const std::vector<float>& heights, std::uint32_t width, std::uint32_t height,
                             double pixel_m, int block) {
  if (width != height || width == 0) {
    throw std::invalid_argument("depth image is " + std::to_string(width) + "x" + std::to_string(height) +
                                ", not square");
  }
  if (block < 1 || width % static_cast<std::uint32_t>(block) != 0) {
    throw std::invalid_argument("block " + std::to_string(block) + " does not divide " + std::to_string(width));
  }
  if (heights.size() != static_cast<std::size_t>(width) * height) {
    throw std::invalid_argument("depth image has " + std::to_string(heights.size()) + " values, not " +
                                std::to_string(static_cast<std::size_t>(width) * height));
  }
  HeightGrid grid;
  grid.size = static_cast<int>(width) / block;
  grid.cell_m = pixel_m * block;
  grid.height_m.assign(static_cast<std::size_t>(grid.size) * grid.size, 0.0f);
  const double scale = 1.0 / (static_cast<double>(block) * block);
  for (int gy = 0; gy < grid.size; ++gy) {
    for (int gx = 0; gx < grid.size; ++gx) {
      double sum = 0.0;
      for (int y = gy * block; y < (gy + 1) * block; ++y) {
        const float* row = heights.data() + static_cast<std::size_t>(y) * width;
        for (int x = gx * block; x < (gx + 1) * block; ++x) sum += row[x];
      }
      grid.height_m[static_cast<std::size_t>(gy) * grid.size + gx] = static_cast<float>(sum * scale);
    }
  }
  return grid;
}

int blockFor(std::uint32_t width, int max_cells) {
  for (int block = 1; block <= static_cast<int>(width); ++block) {
    if (width % static_cast<std::uint32_t>(block) == 0 && static_cast<int>(width) / block <= max_cells) return block;
  }
  return static_cast<int>(width);
}

nlohmann::json heightGridJson(const HeightGrid& grid, std::uint64_t step, std::int64_t t_ns) {
  std::vector<double> mm;
  mm.reserve(grid.height_m.size());
  for (const float h : grid.height_m) mm.push_back(std::round(static_cast<double>(h) * 1e5) / 100.0);
  return {{"type", "depth"}, {"step", step}, {"t_s", static_cast<double>(t_ns) * 1e-9}, {"size", grid.size},
          {"cell_m", grid.cell_m}, {"heights_mm", mm}};
}

}  // namespace climbsim
