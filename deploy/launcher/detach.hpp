#pragma once
/// @file
/// Detaching a supervisor from the terminal (`up -d`): double fork into a new session,
/// with a pipe back to the starting process for "the services are up" or an error.

#include <functional>
#include <string>

namespace climbsim::launcher {

/// The daemon's end of the report pipe.
class DetachReport {
 public:
  explicit DetachReport(int fd) : fd_(fd) {}

  /// Every process has started: the starting process may return.
  void ready();

  /// Starting failed: the starting process prints `message` and exits with `exit_code`.
  void failed(int exit_code, const std::string& message);

 private:
  void send(const std::string& text);
  int fd_;
};

/// Runs `daemon_body` in a daemon: a grandchild in a new session, leading its own process
/// group (pgid = its pid), stdin from /dev/null, stdout and stderr written to `log_file`;
/// it exits with the body's result and never returns here. The calling process returns once the daemon reported:
/// 0 after ready(), the code after failed() (the message printed to stderr), or 1 if the
/// daemon ended without a report. Locks held by the caller are inherited by the daemon.
int runDetached(const std::string& log_file, const std::function<int(DetachReport&)>& daemon_body);

}  // namespace climbsim::launcher
