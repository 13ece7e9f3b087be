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
/// mass, centre-of-mass height, body radius (body.diameter_m / 2), wheel contact points
/// (geometry.wheels), wheel radius, friction coefficient, speed and steering-rate limits.
/// Derived (documented in drive_params.hpp): chassis inertia (uniform disc), Hertz modulus
/// (1 mm penetration when the wheels share adhesion.desired_downforce_n), wheel torque limit
/// (μ F_desired r_w / wheel count), relaxation length (= wheel radius). The rest keep their
/// defaults. Finally validateDriveParams (ConfigError "drive parameters: ...").
DriveParams driveParamsFromRobot(const RobotDescription& description, const RobotGeometry& geometry);

/// The chassis inertia default of DriveParams for the current mass, radii and unit masses.
void setDiscInertia(DriveParams& params);

}  // namespace climbsim::drive
