#pragma once
/// @file
/// Parameters of the sealing model (docs/design.md#sealing-and-leakage), taken from the robot
/// description (and the strips' outline from the scenario).

#include <string>
#include <vector>

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/shard_tiles/strip_masks.hpp"

namespace climbsim::sealing {

struct SealingParams {
  double max_slope = 0.0;     ///< largest height change of the strip per metre along it [m/m], > 0
  double travel_m = 0.0;      ///< the strip extends at most this far below its rest plane z = 0 [m], > 0
  double basic_gap_m = 0.0;   ///< L_basic: the gap the sliding coating always leaves [m], >= 0
  double kappa_L = 0.0;       ///< weight of the mean unclosed gap, >= 0
  std::vector<std::string> segment_names;  ///< geometry order
  std::vector<double> segment_length_m;    ///< l_i, exact (not the polyline's) [m]
  /// Bound each segment's gap area by the channel cross-section along its edge lines
  /// (channel_bound.hpp). Robot file key sealing.channel_bound; off by default: the leakage of
  /// docs/design.md#sealing-and-leakage unchanged.
  bool channel_bound = false;
  /// Which pixels make up a strip (StripMasks): whole pixels by their centres, or every pixel
  /// by the share of its square in the strip. The scenario's depth_camera.subpixel
  /// (docs/design.md#sub-pixel-leakage); pixel centres by default.
  StripOutline strip_outline = StripOutline::kPixelCentres;
};

/// The sealing.* values of the robot and the segments of its geometry.
SealingParams sealingParamsFromRobot(const RobotDescription& robot, const RobotGeometry& geometry);

}  // namespace climbsim::sealing
