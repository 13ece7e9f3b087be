#pragma once
/// @file
/// climbsim-thermo on the lockstep: a ThermoNode between its DDS topics (a part of the
/// executable, not of climbsim_thermo_node, which has no DDS entity).

#include "climbsim/lockstep_participant.hpp"
#include "thermo/configure.hpp"
#include "thermo_node.hpp"

namespace climbsim::thermo {

/// Joins the run as `options` says and steps `node` every due step by the participant's period
/// until the run ends: reads the inputs `inputs` names (Leakage, ValveCommand, EngineCommand),
/// writes ChamberState and AdhesionForce (with the set-point of the last valid ValveCommand;
/// ambient as the trace's row 0). Returns the run's exit code.
int runThermoParticipant(const ParticipantOptions& options, const ThermoNodeInputs& inputs, ThermoNode& node);

}  // namespace climbsim::thermo
