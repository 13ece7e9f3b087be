#pragma once
/// @file
/// Signals as events for poll(): SIGCHLD, SIGINT, SIGTERM and SIGHUP become bytes on a
/// pipe (the self-pipe trick), so the supervisor waits for output, child exits and stop
/// requests in one poll() without races.

#include <vector>

namespace climbsim::launcher {

/// Installs the handlers; restores the default dispositions on destruction. One instance
/// per process at a time. SIGPIPE is handled too (as nothing), so a write to a closed
/// terminal pipe fails with EPIPE instead of killing the supervisor; handled signals are
/// reset to their defaults in started programs by exec.
class SignalEvents {
 public:
  SignalEvents();
  ~SignalEvents();
  SignalEvents(const SignalEvents&) = delete;
  SignalEvents& operator=(const SignalEvents&) = delete;

  /// The descriptor to poll for POLLIN.
  int fd() const;

  /// The stop requests (SIGINT, SIGTERM, SIGHUP) that arrived since the last call, in
  /// order; SIGCHLD only wakes the poll and is not listed.
  std::vector<int> drain();

  /// While an InterruptShield lives, SIGINT is ignored, so that programs started meanwhile
  /// inherit "ignore SIGINT" through exec and the terminal's Ctrl-C reaches only the
  /// supervisor (which then stops the run in order). A Ctrl-C within the shield (a fork
  /// and exec long) is lost.
  class InterruptShield {
   public:
    InterruptShield();
    ~InterruptShield();
    InterruptShield(const InterruptShield&) = delete;
    InterruptShield& operator=(const InterruptShield&) = delete;
  };
};

}  // namespace climbsim::launcher
