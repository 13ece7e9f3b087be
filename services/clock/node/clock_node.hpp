#pragma once
/// @file
/// The clock's DDS adapter: readers -> ClockCore events, ClockCore messages -> writers.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "clock.h"

#include "../model/clock_core.hpp"
#include "climbsim/dds_context.hpp"

namespace climbsim::clock {

/// How a roster participant that DDS lost is, in the words of the clock's Stop reason: from
/// /proc/<pid>/stat when its ParticipantReady's `host` is this host ("its process 123 is
/// stopped (SIGSTOP or a debugger): it exists but does not run", "its process 123 exited",
/// "...; its process 123 exists and runs but sends nothing"), else what DDS said
/// (`liveliness`: its liveliness lapsed; else DDS dropped its writer or participant).
std::string lostWording(bool liveliness, const std::string& host, std::uint32_t pid);

/// Runs one ClockCore on a DDS domain until the run ends.
class ClockNode {
 public:
  /// Creates the DDS participant and the clock's endpoints. `robot`: the run's robot, which
  /// RunStart carries to every participant (robot_shape_idl.hpp); none by default.
  ClockNode(const DdsSettings& dds, ClockParams params, climbsim::RobotShape robot = {});
  ~ClockNode();

  /// Runs the clock; returns the process exit code (climbsim::ExitCode).
  /// Setting `stop_signal` stops the run on request (SIGINT/SIGTERM).
  int run(const std::atomic<bool>& stop_signal);

 private:
  struct Endpoints;
  class Transport;
  class Discovery;
  void feedEvents(ClockCore::Time now);
  void awaitParticipantsLeaving();

  ClockParams params_;
  Notifier notifier_;
  std::unique_ptr<Discovery> discovery_;  ///< before dds_: it outlives the participant
  std::unique_ptr<DdsContext> dds_;
  std::unique_ptr<Endpoints> endpoints_;
  std::unique_ptr<Transport> transport_;
  std::unique_ptr<ClockCore> core_;
};

}  // namespace climbsim::clock
