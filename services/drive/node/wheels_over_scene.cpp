#include "wheels_over_scene.hpp"

#include <Eigen/Geometry>

namespace climbsim::drive {

WheelsOverScene::WheelsOverScene(scene::WallCoverage coverage, std::vector<WheelMount> wheels)
    : coverage_(std::move(coverage)), wheels_(std::move(wheels)), named_(wheels_.size(), 0) {}

std::array<double, 2> WheelsOverScene::contactPoint(const DriveOutputs& outputs, std::size_t w) const {
  const auto& q = outputs.orientation_wxyz;
  const Eigen::Quaterniond R_W_R(q[0], q[1], q[2], q[3]);
  const Eigen::Vector3d p_W = Eigen::Vector3d(outputs.position_m[0], outputs.position_m[1], outputs.position_m[2]) +
                              R_W_R.normalized() * Eigen::Vector3d(wheels_[w].x_m, wheels_[w].y_m, 0.0);
  return {p_W.x(), p_W.y()};
}

std::vector<std::size_t> WheelsOverScene::newlyOverNothing(const DriveOutputs& outputs) {
  std::vector<std::size_t> found;
  for (std::size_t w = 0; w < wheels_.size(); ++w) {
    if (named_[w]) continue;
    const auto p = contactPoint(outputs, w);
    if (!coverage_.covered(p[0], p[1])) {
      named_[w] = 1;
      found.push_back(w);
    }
  }
  return found;
}

}  // namespace climbsim::drive
