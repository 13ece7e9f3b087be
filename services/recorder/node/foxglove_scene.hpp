#pragma once
/// @file
/// The Foxglove channels of a recording (docs/recordings.md#foxglove-channels): the run in
/// Foxglove's own message types, so that its 3D panel shows the robot without any climbsim code.
/// Frames: "wall" (the wall frame W, fixed) and "robot" (R, moving with RobotState).

#include <cstdint>
#include <vector>

#include "climbsim/robot/robot_geometry.hpp"
#include "foxglove_schemas.h"
#include "robot.h"
#include "scene.h"
#include "thermo.h"

namespace climbsim::recorder {

/// Suction p_ambient - p [Pa] at which a chamber is drawn fully red (none: blue).
inline constexpr double kFullSuctionPa = 20000.0;
/// Length of a wheel's load arrow per newton of normal force [m/N].
inline constexpr double kWheelArrowMPerN = 2e-4;
/// Length of the downforce arrow per newton [m/N].
inline constexpr double kDownforceArrowMPerN = 1e-4;

/// foxglove.FrameTransforms: "wall" -> "robot" at t_ns, the pose of `pose` (R's origin in W
/// [m], its orientation as a quaternion).
foxglove::FrameTransforms robotTransform(const climbsim::RobotState& pose, std::int64_t t_ns);

/// Each chamber of `geometry` as triangles in the sealing plane (R's z = 0): its outline
/// polygon, arcs sampled every 6 degrees, cut into triangles (ear clipping), in the order of
/// geometry.chambers; no colour.
std::vector<foxglove::TriangleListPrimitive> chamberShapes(const RobotGeometry& geometry);

/// foxglove.SceneUpdate at t_ns, one entity "robot" in frame "robot" (frame-locked): each
/// chamber of `geometry` (its `shapes`, chamberShapes) coloured by its suction
/// (blue at none, red at kFullSuctionPa; `ambient_pa` is the pressure of no suction), the
/// wheels' normal loads as arrows at their contact points along R's +z, and the downforce as an
/// arrow at P_F towards the wall. Absent samples leave their part out.
foxglove::SceneUpdate robotScene(const RobotGeometry& geometry,
                                 const std::vector<foxglove::TriangleListPrimitive>& shapes,
                                 const climbsim::ChamberState* chambers, double ambient_pa,
                                 const climbsim::DriveState* drive, const climbsim::AdhesionForce* force,
                                 std::int64_t t_ns);

/// foxglove.Grid of a reduced depth image, in frame "robot": one FLOAT32 field "height_m" per
/// cell, rows from R's -y edge up (the DepthGrid's last row first), centred on R's origin.
foxglove::Grid depthGridMessage(const climbsim::DepthGrid& grid);

/// foxglove.Grid of a whole depth image (width_px x height_px pixels of pixel_size_m), laid out
/// as depthGridMessage lays out a grid: field "height_m", rows from R's -y edge up, centred on R's
/// origin. An image with fewer heights than pixels (a tile) gives a grid of zeros.
foxglove::Grid depthImageMessage(const climbsim::DepthImage& image);

}  // namespace climbsim::recorder
