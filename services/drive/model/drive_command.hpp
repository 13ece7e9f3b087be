#pragma once
/// @file
/// Checking drive commands and turning a body command (vx, vy, wz) into per-wheel steering
/// angles and wheel speeds. Pure functions, no Simbody.

#include <string>
#include <vector>

#include "drive_params.hpp"
#include "drive_types.hpp"

namespace climbsim::drive {

/// Commands beyond this multiple of the drive's limits are taken as garbage, not saturated.
inline constexpr double kAbsurdLimitFactor = 10.0;

/// "" if `command` is usable, else one line naming the field and its value. Unusable: any
/// non-finite value; body mode with a wheel surface speed (below) above kAbsurdLimitFactor *
/// max_speed_mps; wheel mode with a vector length other than the wheel count, |steering| >
/// 4π or |wheel speed| > kAbsurdLimitFactor * max_speed_mps / the wheel's radius, a steering
/// set-point other than 0 for a fixed wheel or a caster, or a speed other than 0 for a caster.
/// Usable commands above the limits are saturated by wheelTargets.
std::string checkCommand(const DriveParams& params, const DriveCommand& command);

/// Speed of wheel i's contact point for the body command: |(vx - wz y_i, vy + wz x_i)| [m/s].
double wheelSurfaceSpeed(const WheelMount& wheel, const DriveCommand& command);

/// "" unless the body command asks for a sideways speed (vy != 0) that the robot's fixed
/// wheels cannot give, else one line naming them: they roll at their share of vx and wz
/// only, and vy is ignored for them.
std::string sidewaysNote(const DriveParams& params, const DriveCommand& command);

/// Steering and wheel-speed targets for a usable command. Body mode (the robot's kinematics,
/// rigid body in the wall plane): a steerable wheel i must move its contact point at
/// v_i = (vx - wz y_i, vy + wz x_i); a fixed wheel rolls along R's x at vx - wz y_i (it cannot
/// move sideways: vy is ignored); a caster gets nothing (steering 0, speed 0: it is not
/// driven). The whole command is scaled by one factor so that no driven wheel exceeds
/// max_speed_mps (keeps the path's shape). A steerable wheel's heading is atan2(v_i): of the
/// two equivalent set-points (heading, +|v_i|/r_w) and (heading ± π, -|v_i|/r_w) the one
/// closer to `previous` is taken, so that no wheel is asked to steer by more than 90°; one
/// asked for (almost) no speed keeps its previous steering. Wheel mode: the steering
/// set-points as given, speeds clamped to ±max_speed_mps / r_w.
std::vector<WheelSetpoint> wheelTargets(const DriveParams& params, const DriveCommand& command,
                                        const std::vector<WheelSetpoint>& previous);

}  // namespace climbsim::drive
