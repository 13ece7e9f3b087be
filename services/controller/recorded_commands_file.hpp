#pragma once
/// @file
/// A recorded controller's commands from a run.mcap (docs/recordings.md#replaying-commands): the
/// controller/ValveCommand and controller/EngineCommand samples a run with
/// `recording.commands: true` wrote, decoded, checked against the robot, in order.

#include <string>

#include "climbsim/robot/robot_geometry.hpp"
#include "model/recorded_commands.hpp"

namespace climbsim::controller {

/// The commands recorded in `file`. ConfigError, one line naming the file and what is wrong, if
/// the file is no whole recording, holds no command channel (the run was recorded without
/// `recording.commands`), a sample does not decode, comes from a second writer, goes back in
/// time, or does not fit the robot (a valve opening or engine speed outside [0, 1] or not
/// finite, another number of valves than `geometry`'s chambers with a reservoir, of engines
/// than `engine_count`), or the recording stops before `duration_ns`.
RecordedCommands readRecordedCommands(const std::string& file, const RobotGeometry& geometry, int engine_count,
                                      std::int64_t duration_ns);

}  // namespace climbsim::controller
