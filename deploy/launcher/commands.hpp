#pragma once
/// @file
/// The launcher's commands: up, run, down, ps, logs. Each returns the process exit code
/// and throws ConfigError (exit code 2) for a bad compose file.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace climbsim::launcher {

/// What every command is given.
struct CommandContext {
  std::string root;          ///< the repository (absolute)
  std::string build_dir;     ///< the build directory (absolute): bin/ and run/ are in it
  std::string compose_file;  ///< the compose file (-f, default <root>/deploy/compose.yaml)
};

/// Options of `up` and `run`.
struct UpOptions {
  bool detach = false;   ///< `up -d`: supervise in a daemon, print the run directory
  std::string out_dir;   ///< `run --out DIR`: also write the logs to DIR/logs; the run's ${out}
  /// A scenario file, or a name in <root>/deploy/scenarios (NAME.yaml); empty: the compose
  /// file's `scenario:`, if any.
  std::string scenario;
  std::vector<std::string> overrides;  ///< --set key=value for the scenario
  std::optional<std::uint32_t> window_steps;  ///< --window-steps: replaces the compose file's clock.window_steps
};

/// Starts the clock and every service and supervises them (see Supervisor); in the
/// foreground it returns the run's exit code once every process has ended.
int commandUp(const CommandContext& context, const UpOptions& options);

/// Stops the running composition: asks the clock to stop, waits up to 10 s for the
/// supervisor, then SIGTERM and SIGKILL. Idempotent.
int commandDown(const CommandContext& context);

/// Prints a table of the processes: name, pid, state.
int commandPs(const CommandContext& context);

/// Prints the log files: every process's prefixed, or one process's (or service's) as is.
int commandLogs(const CommandContext& context, const std::string& service);

}  // namespace climbsim::launcher
