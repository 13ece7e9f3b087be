#pragma once
/// @file
/// The default robot (deploy/robots/cromsci.yaml) and grids for the sealing tests.

#include <string>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/depth_grid.hpp"
#include "sealing_model.hpp"
#include "climbsim/shard_tiles/sealing_params.hpp"

#ifndef CLIMBSIM_ROBOTS_DIR
#error "CLIMBSIM_ROBOTS_DIR must name deploy/robots"
#endif

namespace climbsim::sealing::testing {

inline std::string robotFile() { return std::string(CLIMBSIM_ROBOTS_DIR) + "/cromsci.yaml"; }

inline const RobotDescription& robot() {
  static const RobotDescription r = loadRobotDescription(robotFile());
  return r;
}

inline const RobotGeometry& geometry() {
  static const RobotGeometry g = computeGeometry(robot());
  return g;
}

/// W x H pixels over a view `view_m` wide (square pixels).
inline PixelGrid grid(int width_px, int height_px, double view_m = 0.80) {
  return PixelGrid{width_px, height_px, view_m / width_px};
}

/// The default robot's sealing on `g`, its strips outlined by `outline`.
inline SealingModel model(const PixelGrid& g, StripOutline outline = StripOutline::kPixelCentres) {
  SealingParams params = sealingParamsFromRobot(robot(), geometry());
  params.strip_outline = outline;
  return SealingModel(params, geometry(), g, robotFile());
}

/// Both outlines of the strips (depth_camera.subpixel off and on).
inline constexpr StripOutline kOutlines[] = {StripOutline::kPixelCentres, StripOutline::kSubpixelShares};

/// "pixel centres" or "sub-pixel shares", for a test's messages.
inline const char* outlineName(StripOutline outline) {
  return outline == StripOutline::kPixelCentres ? "pixel centres" : "sub-pixel shares";
}

}  // namespace climbsim::sealing::testing
