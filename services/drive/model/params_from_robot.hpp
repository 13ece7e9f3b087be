#pragma once
/// @file
/// The drive model's parameters from the robot description and its geometry, so that
/// nothing of the robot is typed in twice (deploy/robots/*.yaml is the only source).

#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "drive_params.hpp"

namespace climbsim::drive {

/// DriveParams of a robot. Validates the description first (validateRobotDescription:
/// ConfigError "robot <name>: <dotted.key> = <value>: <why>", e.g. body.mass_kg = 0,
/// wheels.friction_coefficient < 0, a wheel outside its chamber), then takes from it:
/// mass, centre-of-mass height, body radius (the body outline's farthest point:
/// body.diameter_m / 2, or half the rectangle's diagonal), each wheel's kind, mount
/// (geometry.wheels), radius and friction coefficient, speed and steering-rate limits.
/// Derived (documented in drive_params.hpp): chassis inertia (uniform disc or box), Hertz
/// modulus (1 mm penetration of the smallest wheel when the wheels share
/// adhesion.desired_downforce_n), wheel torque limit (μ F_desired r_w / wheel count, the
/// largest of the driven wheels), relaxation length (= the wheel's radius), a caster's trail
/// (= its radius). The rest keep their defaults. Finally validateDriveParams (ConfigError
/// "drive parameters: ...").
DriveParams driveParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry);

/// The chassis inertia of a circular body: a uniform disc (DriveParams::inertia_*) for the
/// current mass, radii and unit masses.
void setDiscInertia(DriveParams& params);

/// The chassis inertia of a rectangular body of `length_m` (x) by `width_m` (y): a uniform
/// box of thickness 2 com_height_m (DriveParams::inertia_*) for the current mass and unit
/// masses.
void setBoxInertia(DriveParams& params, double length_m, double width_m);

}  // namespace climbsim::drive
