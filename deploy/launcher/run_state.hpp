#pragma once
/// @file
/// The run directory of a composition (<build>/run/<name>/) and its state.json: who
/// supervises the run, on which domain, and the pid and fate of every process.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace climbsim::launcher {

/// Paths inside one composition's run directory.
struct RunPaths {
  /// <build_dir>/run/<run_name>
  RunPaths(const std::string& build_dir, const std::string& run_name);

  std::string dir;             ///< the run directory
  std::string logs_dir;        ///< <dir>/logs: one <process>.log per process
  std::string state_file;      ///< <dir>/state.json
  std::string lock_file;       ///< <dir>/supervisor.lock: held by the live supervisor, holds its pid
  std::string supervisor_log;  ///< <dir>/supervisor.log: what a detached supervisor says

  /// <logs_dir>/<process>.log
  std::string logFile(const std::string& process) const;
};

/// One supervised process.
struct ProcessState {
  std::string name;                ///< "clock" or a roster name
  pid_t pid = -1;
  std::optional<int> exit_code;    ///< once it has ended (128 + signal if a signal ended it)
  std::string host = "local";      ///< the compose file's host it runs on
  std::optional<double> cpu_s;     ///< user + system CPU time [s], once it has ended (ssh: the client's)
  std::optional<std::uint64_t> ctx_switches;  ///< context switches of all its threads, once it has ended
};

/// What state.json holds.
struct RunState {
  std::string name;                  ///< the run name (`--name`, default from the scenario)
  std::string compose_name;
  std::string compose_file;
  std::string run_dir;
  pid_t supervisor_pid = -1;
  bool detached = false;             ///< a detached supervisor leads its own process group
  int domain_id = -1;
  std::string started_at;            ///< ISO 8601, local time
  std::string scenario;              ///< the scenario file the run was started with, or empty
  std::string out_dir;               ///< the run's output directory (trace, summary), or empty
  double rtf = 0.0;                  ///< the clock's real-time factor (0: as fast as possible)
  std::string viewer_url;            ///< where the run's viewer serves its page, once it said so; "" none
  std::vector<ProcessState> processes;  ///< the clock first
  std::optional<int> exit_code;      ///< the supervisor's, once the run is over
};

/// state.json text.
std::string runStateToJson(const RunState& state);

/// Parses state.json text; throws std::runtime_error naming `source` if it is malformed.
RunState runStateFromJson(const std::string& text, const std::string& source);

/// Writes `state` to `path` atomically (a temporary file renamed over it).
void writeRunState(const std::string& path, const RunState& state);

/// Reads `path`; nothing if it does not exist; throws std::runtime_error if malformed.
std::optional<RunState> readRunState(const std::string& path);

/// The local time now as "2024-05-01T12:34:56".
std::string localTimestamp();

}  // namespace climbsim::launcher
