#include "climbsim/shard_tiles/sealing_graph.hpp"

#include <cmath>
#include <stdexcept>

namespace climbsim::sealing {

Neighbourhood::Neighbourhood(double max_slope, double pixel_size_m) {
  if (!(max_slope > 0.0) || !(pixel_size_m > 0.0)) {
    throw std::invalid_argument("Neighbourhood: max_slope and pixel_size_m must be > 0");
  }
  for (std::size_t j = 0; j < kOffsets.size(); ++j) {
    step_m[j] = j < 4 ? max_slope * pixel_size_m : max_slope * pixel_size_m * std::sqrt(2.0);
  }
}

SealingSubgraph wholeSealingGraph(const StripMasks& masks) {
  const PixelGrid& g = masks.grid();
  const auto& pixels = masks.sealingPixels();
  SealingSubgraph graph;
  graph.sealing_index.resize(pixels.size());
  graph.neighbours.assign(pixels.size() * 8, -1);
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    graph.sealing_index[k] = static_cast<std::uint32_t>(k);
    const int r = static_cast<int>(pixels[k] / g.width_px);
    const int c = static_cast<int>(pixels[k] % g.width_px);
    for (std::size_t j = 0; j < 8; ++j) {
      const int nr = r + Neighbourhood::kOffsets[j][0];
      const int nc = c + Neighbourhood::kOffsets[j][1];
      if (nr < 0 || nr >= g.height_px || nc < 0 || nc >= g.width_px) continue;
      graph.neighbours[8 * k + j] = masks.sealingIndexOfPixel(static_cast<std::size_t>(nr) * g.width_px + nc);
    }
  }
  return graph;
}

}  // namespace climbsim::sealing
