#include "sealing_translate.hpp"

#include <algorithm>
#include <limits>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace climbsim::sealing {

std::string checkDepthImage(const climbsim::DepthImage& sample, const PixelGrid& camera) {
  std::ostringstream why;
  if (!std::isfinite(sample.near_m()) || !std::isfinite(sample.far_m()) || !(sample.near_m() > sample.far_m())) {
    why << "near_m = " << sample.near_m() << ", far_m = " << sample.far_m() << " (need finite near_m > far_m)";
    return why.str();
  }
  const std::string grid_problem = checkDepthGrid(depthGridFromIdl(sample), camera);
  if (!grid_problem.empty()) return grid_problem;
  // The camera clamps to [far, near]; 1 µm covers float rounding of the bounds.
  constexpr double kTolerance_m = 1e-6;
  const auto& h = sample.height_m();
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (h[i] < sample.far_m() - kTolerance_m || h[i] > sample.near_m() + kTolerance_m) {
      why << "pixel (row " << i / camera.width_px << ", col " << i % camera.width_px << ") height_m = " << h[i]
          << " outside [far_m, near_m] = [" << sample.far_m() << ", " << sample.near_m() << "]";
      return why.str();
    }
  }
  return {};
}

DepthGrid depthGridFromIdl(const climbsim::DepthImage& sample) {
  DepthGrid depth;
  depth.grid.width_px = static_cast<int>(sample.width_px());
  depth.grid.height_px = static_cast<int>(sample.height_px());
  depth.grid.pixel_size_m = sample.pixel_size_m();
  depth.height_m = sample.height_m();
  // The image's highest pixel: it bounds how far a shard's region must reach.
  float highest = -std::numeric_limits<float>::infinity();
  for (const float h : depth.height_m) highest = std::max(highest, h);
  depth.upper_bound_m = highest;
  return depth;
}

climbsim::DepthImage depthImageToIdl(const DepthGrid& depth, double far_m, double near_m) {
  climbsim::DepthImage sample;
  sample.width_px(static_cast<std::uint32_t>(depth.grid.width_px));
  sample.height_px(static_cast<std::uint32_t>(depth.grid.height_px));
  sample.pixel_size_m(depth.grid.pixel_size_m);
  sample.near_m(near_m);
  sample.far_m(far_m);
  sample.quantised_8bit(false);
  sample.height_m(depth.height_m);
  return sample;
}

climbsim::Leakage leakageToIdl(const std::vector<std::string>& names, const std::vector<SegmentLeak>& leaks,
                               const std::vector<std::size_t>& indices) {
  if (indices.size() > 64) throw std::invalid_argument("Leakage holds at most 64 segments");
  climbsim::Leakage sample;
  for (const std::size_t i : indices) {
    if (names.at(i).size() > 31) throw std::invalid_argument("segment name '" + names[i] + "' longer than 31");
    climbsim::LeakageSegment s;
    s.segment(names[i]);
    s.leak_area_m2(leaks.at(i).leak_area_m2);
    s.mean_gap_m(leaks.at(i).mean_gap_m);
    sample.segments().push_back(s);
  }
  return sample;
}

climbsim::SealingImage sealingImageToIdl(const std::string& source, std::uint64_t step, std::int64_t t_ns,
                                         const std::string& kind, const std::vector<unsigned char>& png) {
  climbsim::SealingImage sample;
  sample.source(source);
  sample.step(step);
  sample.t_ns(t_ns);
  sample.kind(kind);
  sample.png(png);
  return sample;
}

}  // namespace climbsim::sealing
