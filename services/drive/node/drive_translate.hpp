#pragma once
/// @file
/// Translators between the drive topics (idl/robot.idl, idl/thermo.idl) and the model's
/// inputs and outputs. Pure functions: no DDS entity, tested without a network. The stamp
/// fields (source, step, t_ns) are left to StampedOutput::write.

#include "climbsim/topic_names.hpp"
#include "drive_types.hpp"
#include "robot.h"
#include "thermo.h"

namespace climbsim::drive {

/// Topic names: the one list of common/include/climbsim/topic_names.hpp (topic::kLeakage, ...).
namespace topic = climbsim::topic;

/// The command as sent (checks are the model's: checkCommand).
DriveCommand driveCommandFromIdl(const climbsim::DriveCommand& sample);
climbsim::DriveCommand driveCommandToIdl(const DriveCommand& command);

/// Copies F [N] and P_F [m, robot frame] of `sample` into `inputs` (the command stays).
void applyAdhesion(const climbsim::AdhesionForce& sample, DriveInputs& inputs);
climbsim::AdhesionForce adhesionForceToIdl(double downforce_n, double pf_x_m, double pf_y_m);

/// Pose and twist of R in W, and `fell`.
climbsim::RobotState robotStateToIdl(const DriveOutputs& outputs);
/// Per wheel steering, speed, normal force, slip; `fell`. std::invalid_argument beyond 8 wheels.
climbsim::DriveState driveStateToIdl(const DriveOutputs& outputs);
/// The same into `sample` (every field but the stamp): a sample kept from step to step is
/// filled without allocating.
void driveStateToIdl(const DriveOutputs& outputs, climbsim::DriveState& sample);

}  // namespace climbsim::drive
