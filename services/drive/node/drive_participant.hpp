#pragma once
/// @file
/// climbsim-drive on the lockstep: a DriveNode between its DDS topics (a part of the
/// executable, not of climbsim_drive_node, which has no DDS entity).

#include "climbsim/lockstep_participant.hpp"
#include "drive/configure.hpp"
#include "drive_node.hpp"

namespace climbsim::drive {

/// Joins the run as `options` says and steps `node` every due step by the participant's period
/// until the run ends: reads the inputs setup.inputs names (DriveCommand, AdhesionForce), writes
/// RobotState and DriveState (the start pose at rest as the trace's row 0), names each wheel
/// that comes to stand over nothing of setup.scene_file (the check loads while the participant
/// joins) and reports a fall (ends the run if setup.end_on_fall). Returns the run's exit code.
int runDriveParticipant(const ParticipantOptions& options, const DriveSetup& setup, DriveNode& node);

}  // namespace climbsim::drive
