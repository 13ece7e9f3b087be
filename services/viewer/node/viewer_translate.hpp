#pragma once
/// @file
/// IDL samples -> the viewer's model (live_state.hpp) and a page's clock request ->
/// ClockControl. Pure functions: no DDS entity, tested without a network.

#include <map>
#include <optional>
#include <set>
#include <string>

#include "client_command.hpp"
#include "clock.h"
#include "live_state.hpp"
#include "climbsim/height_grid.hpp"
#include "record.h"
#include "robot.h"
#include "scene.h"
#include "sealing.h"
#include "thermo.h"

namespace climbsim::viewer {

ForceValue forceFromIdl(const climbsim::AdhesionForce& sample);
ChamberValue chambersFromIdl(const climbsim::ChamberState& sample);
PoseValue poseFromIdl(const climbsim::RobotState& sample);
WheelsValue wheelsFromIdl(const climbsim::DriveState& sample);
LeakValue leakFromIdl(const climbsim::Leakage& sample);

/// A DepthGrid as a height grid; nothing if its heights are not size * size.
std::optional<HeightGrid> gridFromIdl(const climbsim::DepthGrid& sample);

/// The topics some roster member of `run` records (RosterEntry.recorded_topics): their
/// producers send them in record batches.
std::set<std::string> recordedTopics(const climbsim::RunStart& run);
/// The last sample of each topic in `batch` (samples are in step order): latest value wins.
std::map<std::string, const climbsim::RecordedSample*> latestPerTopic(const climbsim::RecordBatch& batch);
/// "a, b, c" for logs.
std::string joinedTopics(const std::set<std::string>& topics);

/// SimTime: time, pacing target, running or paused (unless the run has ended).
void applySimTime(RunInfo& run, const climbsim::SimTime& sample);
/// RunStart: step length, end, roster; the run is running from now on.
void applyRunStart(RunInfo& run, const climbsim::RunStart& sample);
/// Stop: completed, stopped on request, or failed with its reason (and culprit).
void applyStop(RunInfo& run, const climbsim::Stop& sample);
/// ParticipantReady: the participant's host.
void applyReady(RunInfo& run, const climbsim::ParticipantReady& sample);

/// The ClockControl sample of a request, with `sender` (the viewer's name).
climbsim::ClockControl controlToIdl(const ClockRequest& request, const std::string& sender);

}  // namespace climbsim::viewer
