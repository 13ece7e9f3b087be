#include "climbsim/robot/depth_view.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim {

double robotDepthViewM(const RobotGeometry& geometry) {
  double reach_m = 0.0;  // max(|x|, |y|) of every strip centre-line point
  for (const auto& segment : geometry.segments) {
    for (const auto& p : segment.centreline_Robot) reach_m = std::max({reach_m, std::abs(p.x_m), std::abs(p.y_m)});
  }
  const double half_m = reach_m + geometry.strip_width_m / 2.0 + kDepthViewMarginM;
  const double steps = std::ceil(2.0 * half_m * 1000.0 / kDepthViewStepMm - 1e-9);
  return std::max(1.0, steps) * kDepthViewStepMm / 1000.0;
}

}  // namespace climbsim
