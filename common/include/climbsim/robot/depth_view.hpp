#pragma once
/// @file
/// The depth camera's view a robot needs (docs/robot-files.md#the-depth-cameras-view): the side
/// of the square of wall, centred on the robot frame's origin, that the depth image covers
/// unless a scenario, scene or command line says otherwise. The scene renders it, the sealing
/// reads it, the launcher checks that both agree and solo runs both: all take it from here.

#include "climbsim/robot/robot_geometry.hpp"

namespace climbsim {

/// Room left between the outermost strip edge and the image's edge [m].
inline constexpr double kDepthViewMarginM = 0.02;
/// The view's side is a whole number of these [mm] (0.1 m).
inline constexpr int kDepthViewStepMm = 100;

/// Side of the robot's default depth view [m]: the smallest square centred on the origin of R
/// that holds every sealing strip (its centre line's points plus half the strip width, as the
/// sealing's strip masks test them) with kDepthViewMarginM to spare, rounded up to a multiple
/// of kDepthViewStepMm:
///   h = max over segments, centre-line points p of max(|p_x|, |p_y|) + w/2 + margin,
///   side = ceil(2 h / step) * step.
/// The default robot (strips out to r = 0.36 m, w = 0.02 m): h = 0.39 m, side 0.80 m.
/// Returned as (steps * kDepthViewStepMm) / 1000.0, so a side of 0.8 m is the double 0.8.
double robotDepthViewM(const RobotGeometry& geometry);

}  // namespace climbsim
