#pragma once
/// @file
/// Errors and process exit codes shared by every climbsim executable.

#include <stdexcept>
#include <string>
#include <vector>

namespace climbsim {

/// Bad configuration or input: the message is one line naming the file or option, the
/// key and the value. Executables print it and exit with ExitCode::kConfig.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The run cannot start for a reason that a fresh start removes (no step was computed):
/// executables print it and exit with kExitRetryStart, and the launcher starts the run again.
class RetryableStartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A ConfigError about one line of a file (0: no line), so that the problems of a file can be
/// reported together in line order (climbsim::ErrorList).
class ConfigErrorAt : public ConfigError {
 public:
  ConfigErrorAt(const std::string& message, int line) : ConfigError(message), line_(line) {}
  int line() const { return line_; }

 private:
  int line_ = 0;
};

/// Collects the problems of one file, as a compiler does: every check runs, and all problems
/// are reported at once, one line each, in line order.
class ErrorList {
 public:
  /// Most problems one report lists; a last line says how many more there were.
  static constexpr std::size_t kMaxReported = 20;

  /// Runs `body`; a ConfigError it throws is recorded instead of ending the caller. True if
  /// `body` ran through.
  template <typename Body>
  bool check(Body&& body) {
    try {
      body();
      return true;
    } catch (const ConfigErrorAt& e) {
      add(e.line(), e.what());
    } catch (const ConfigError& e) {
      add(0, e.what());
    }
    return false;
  }

  /// Records one problem found at `line` (0: not at a line; those come first).
  void add(int line, const std::string& message);

  bool empty() const { return problems_.empty(); }

  /// Throws ConfigError with every recorded problem, one per line, in line order; nothing if
  /// there is none.
  void throwIfAny() const;

 private:
  struct Problem {
    int line;
    std::string message;
  };
  std::vector<Problem> problems_;
};

/// Exit codes of every climbsim executable.
enum ExitCode : int {
  kExitOk = 0,            ///< the run completed (end time reached)
  kExitFailed = 1,        ///< the run failed: a participant failed, vanished or timed out
  kExitConfig = 2,        ///< bad configuration or command line
  kExitStartTimeout = 3,  ///< the roster was not complete within the start timeout
  kExitStopped = 4,       ///< stopped on request (ClockControl STOP, SIGINT/SIGTERM) before the end
  kExitFell = 5,          ///< the robot fell (left the wall) and the scenario ends a run on a fall
  /// the run could not start for a reason a fresh start removes (RetryableStartError: a DDS
  /// Security handshake that stalled); nothing was computed (75: EX_TEMPFAIL of sysexits.h)
  kExitRetryStart = 75,
};

}  // namespace climbsim
