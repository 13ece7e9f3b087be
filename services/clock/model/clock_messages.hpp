#pragma once
/// @file
/// The clock's messages in plain C++ (mirrors of idl/clock.idl, no DDS): what the clock
/// core receives and publishes. The node translates them to and from the IDL types.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "climbsim/schedule.hpp"

namespace climbsim::clock {

/// A participant's schedule and its data topics (IDL RosterEntry).
struct RosterEntry {
  std::string participant;
  Schedule schedule;
  std::vector<std::string> input_topics;
  std::vector<std::string> output_topics;
  std::vector<std::string> same_step_inputs;  ///< inputs read with lag 0 (subset of input_topics)
  std::vector<std::string> recorded_topics;   ///< topics read through record batches (recorders)
  std::vector<std::string> input_sources;     ///< "topic=producer": inputs read from some producers only
};

/// A participant announces it is ready (IDL ParticipantReady).
struct ReadyMsg {
  RosterEntry entry;
  std::vector<std::pair<std::string, std::string>> idl_hashes;  ///< {file, sha256}
  std::string host;
  std::uint32_t pid = 0;
};

enum class DoneKind { kStepDone, kArmed, kFailed, kFell };

/// A participant's progress (every due step below progress_step is done), armed, or
/// failed (IDL StepDone).
struct DoneMsg {
  std::string participant;
  std::uint64_t run_id = 0;
  std::uint64_t progress_step = 0;
  DoneKind kind = DoneKind::kStepDone;
  std::string message;
};

enum class ControlCommand { kPause, kResume, kSingleStep, kStop, kSetRealtimeFactor };

/// A pause, resume, single-step, stop or pacing command (IDL ClockControl).
struct ControlMsg {
  ControlCommand command = ControlCommand::kPause;
  std::uint32_t steps = 1;       ///< kSingleStep: how many steps
  double realtime_factor = 0.0;  ///< kSetRealtimeFactor: >= 0
  std::string sender;
};

/// The whole roster's schedule, published once every participant is ready (IDL RunStart).
struct RunStartMsg {
  std::uint64_t run_id = 0;
  std::int64_t dt_ns = 0;
  std::uint64_t end_step = 0;
  std::uint32_t window_steps = 1;   ///< W: how far the horizon may run ahead of the slowest
  std::vector<RosterEntry> roster;  ///< sorted by participant name
};

/// Every due step below horizon_step may be computed (IDL StepGrant).
struct GrantMsg {
  std::uint64_t run_id = 0;
  std::uint64_t horizon_step = 0;
  std::int64_t t_ns = 0;
  std::int64_t dt_ns = 0;
};

enum class StopKind { kCompleted, kRequested, kFailed, kFell };

/// The end of the run (IDL Stop).
struct StopMsg {
  std::uint64_t run_id = 0;
  std::uint64_t last_step = 0;  ///< last step of the run: the horizon - 1 (0 before any grant)
  std::int64_t t_ns = 0;
  StopKind kind = StopKind::kCompleted;
  std::string culprit;  ///< participant to blame, if any
  std::string reason;
};

/// Best-effort time broadcast (IDL SimTime): `step` is the step every participant reached.
struct SimTimeMsg {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;
  double realtime_factor = 0.0;
  bool paused = false;
};

}  // namespace climbsim::clock
