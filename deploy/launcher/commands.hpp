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
  bool compose_given = false;  ///< -f was given: `ps`, `logs`, `down` keep only its runs
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
  /// `--name`: the run name (run directory <build>/run/NAME, `ps`, `logs`, `down`); empty: the
  /// scenario's name (else the compose file's), with -2, -3, ... while such a run is running.
  std::string name;
  std::optional<double> rtf;   ///< `--rtf X`: the clock's real-time factor instead of the file's
  std::optional<int> domain;   ///< `--domain N`: this DDS domain instead of the file's domain_id
  bool check = false;          ///< `--check`: validate compose, scenario, robot and scene; run nothing
  bool secure = false;         ///< `--secure`: DDS Security as with `security: on`
  /// Start the compose file's observers (`observer: true`, the viewer): `up` does, `run` only
  /// with --viewer.
  bool observers = true;
};

/// Options of `view`.
struct ViewOptions {
  std::string run_dir;            ///< a finished run directory (trace.csv, scenario.yaml)
  int port = 8765;                ///< TCP port of the page
  std::string bind = "127.0.0.1"; ///< address to listen on
  std::string snapshot;           ///< --snapshot PNG: write a picture of the page instead of serving it
  std::optional<double> at_s;     ///< --at T [s]: the time of the snapshot (default: the run's end)
};

/// Starts the clock and every service and supervises them (see Supervisor); in the
/// foreground it returns the run's exit code once every process has ended.
int commandUp(const CommandContext& context, const UpOptions& options);

/// Serves the replay of a finished run directory (climbsim-viewer --replay) until interrupted.
/// A directory without trace.csv or scenario.yaml is a ConfigError naming it.
int commandView(const CommandContext& context, const ViewOptions& options);

/// Stops the run `name` (empty: the only one running; `all`: every running run): asks its
/// clock to stop, waits up to 10 s for the supervisor, then SIGTERM and SIGKILL. Idempotent.
int commandDown(const CommandContext& context, const std::string& name, bool all);

/// Without `name`: one line per run (name, state, domain, scenario), then the processes of
/// each running run. With `name`: that run's processes: name, host, pid, state.
int commandPs(const CommandContext& context, const std::string& name);

/// Prints the log files of run `name` (empty: the only one running, else the last one):
/// every process's prefixed, or one process's (or service's) as is.
int commandLogs(const CommandContext& context, const std::string& name, const std::string& service);

}  // namespace climbsim::launcher
