#pragma once
/// @file
/// Child processes for the launcher and the integration tests: spawn with the output
/// sent to a file or a pipe, signal, wait with a deadline.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace climbsim {

/// What to start.
struct ProcessSpec {
  std::vector<std::string> argv;              ///< argv[0] is the executable (PATH is searched)
  std::map<std::string, std::string> env;     ///< added to (or replacing in) the parent's environment
  std::string output_file;                    ///< stdout and stderr go here (appended) if set
  int output_fd = -1;                         ///< ... or to this descriptor if >= 0
  bool die_with_parent = true;                ///< SIGKILL the child if the parent dies
};

/// A started child. The destructor kills a child that is still running.
class ChildProcess {
 public:
  /// Starts the child; throws std::runtime_error naming argv[0] if it cannot.
  explicit ChildProcess(const ProcessSpec& spec);
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }

  /// The exit code if the child has ended (128 + signal number if a signal ended it).
  std::optional<int> poll();

  /// Waits until the child ends or `timeout` passes; the exit code, or nothing.
  std::optional<int> waitFor(std::chrono::milliseconds timeout);

  /// Sends a signal (SIGKILL, SIGTERM, ...) if it still runs.
  void signal(int signal_number);

  /// User plus system CPU time [s] the child used (with its waited-for children), known once
  /// poll() or waitFor() has seen it end.
  std::optional<double> cpuSeconds() const { return cpu_seconds_; }
  /// Voluntary + involuntary context switches of the ended child, all its threads
  /// (wait4's rusage: the kernel's counters that /proc/PID/status shows while it runs).
  std::optional<std::uint64_t> contextSwitches() const { return context_switches_; }

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  std::optional<double> cpu_seconds_;
  std::optional<std::uint64_t> context_switches_;
};

/// The exit code encoded in a waitpid() status (128 + signal for a signal).
int exitCodeFromStatus(int status);

}  // namespace climbsim
