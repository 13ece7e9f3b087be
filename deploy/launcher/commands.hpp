#pragma once
/// @file
/// The launcher's commands: up, run, down, ps, logs. Each returns the process exit code
/// and throws ConfigError (exit code 2) for a bad compose file.

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
  /// Start the compose file's observers (`observer: true`, the viewer): `up` does, `run` only
  /// with --viewer.
  bool observers = true;
};

/// Options of `view`.
struct ViewOptions {
  std::string run_dir;            ///< a finished run directory (trace.csv, scenario.yaml)
  int port = 8765;                ///< TCP port of the page
  std::string bind = "127.0.0.1"; ///< address to listen on
};

/// Starts the clock and every service and supervises them (see Supervisor); in the
/// foreground it returns the run's exit code once every process has ended.
int commandUp(const CommandContext& context, const UpOptions& options);

/// Serves the replay of a finished run directory (climbsim-viewer --replay) until interrupted.
/// A directory without trace.csv or scenario.yaml is a ConfigError naming it.
int commandView(const CommandContext& context, const ViewOptions& options);

/// Stops the running composition: asks the clock to stop, waits up to 10 s for the
/// supervisor, then SIGTERM and SIGKILL. Idempotent.
int commandDown(const CommandContext& context);

/// Prints a table of the processes: name, pid, state.
int commandPs(const CommandContext& context);

/// Prints the log files: every process's prefixed, or one process's (or service's) as is.
int commandLogs(const CommandContext& context, const std::string& service);

}  // namespace climbsim::launcher
