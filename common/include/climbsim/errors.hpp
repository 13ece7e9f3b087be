#pragma once
/// @file
/// Errors and process exit codes shared by every climbsim executable.

#include <stdexcept>
#include <string>

namespace climbsim {

/// Bad configuration or input: the message is one line naming the file or option, the
/// key and the value. Executables print it and exit with ExitCode::kConfig.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exit codes of every climbsim executable.
enum ExitCode : int {
  kExitOk = 0,            ///< the run completed (end time reached)
  kExitFailed = 1,        ///< the run failed: a participant failed, vanished or timed out
  kExitConfig = 2,        ///< bad configuration or command line
  kExitStartTimeout = 3,  ///< the roster was not complete within the start timeout
  kExitStopped = 4,       ///< stopped on request (ClockControl STOP, SIGINT/SIGTERM) before the end
  kExitFell = 5,          ///< the robot fell (left the wall) and the scenario ends a run on a fall
};

}  // namespace climbsim
