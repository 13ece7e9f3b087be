#pragma once
/// @file
/// IDL samples (idl/clock.idl) <-> the clock core's plain messages.

#include "../model/clock_messages.hpp"
#include "clockPubSubTypes.h"

namespace climbsim::clock {

ReadyMsg fromIdl(const climbsim::ParticipantReady& idl);
DoneMsg fromIdl(const climbsim::StepDone& idl);
ControlMsg fromIdl(const climbsim::ClockControl& idl);
RosterEntry fromIdl(const climbsim::RosterEntry& idl);

climbsim::RosterEntry toIdl(const RosterEntry& msg);
climbsim::RunStart toIdl(const RunStartMsg& msg);
climbsim::StepGrant toIdl(const GrantMsg& msg);
climbsim::Stop toIdl(const StopMsg& msg);
climbsim::SimTime toIdl(const SimTimeMsg& msg);

}  // namespace climbsim::clock
