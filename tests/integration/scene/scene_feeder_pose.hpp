#pragma once
/// @file
/// The robot's path the scene feeder writes and the integration test re-computes.

#include <cmath>
#include <cstdint>

#include "climbsim/wall/triangle_mesh.hpp"

namespace climbsim::scene::testing {

/// T_W_R at feeder step k: the sealing plane 20 mm above the lower wall level, starting at
/// x 0.1 m, y -0.1 m, drifting 2 mm per step along x_W and turning 0.02 rad per step.
inline Pose feederPose(std::uint64_t step) {
  const double k = static_cast<double>(step);
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(0.3 + 0.02 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.1 + 0.002 * k, -0.1, 0.02);
  return T;
}

}  // namespace climbsim::scene::testing
