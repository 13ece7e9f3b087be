#pragma once
/// @file
/// From a compose file to the command lines of one run: the clock with its roster, and
/// every service instance with --name, --period, --offset and --domain appended.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compose_file.hpp"

namespace climbsim::launcher {

/// One process to start.
struct ProcessLaunch {
  std::string name;               ///< "clock" or a roster name (log file, prefix, `ps`)
  std::string host = kLocalHost;  ///< the compose file's host it runs on
  /// What the launcher executes: the program's argv, behind `ip netns exec NS` or `ssh` for
  /// a host of that kind (argv[0] is then `ip` or `ssh`).
  std::vector<std::string> argv;
  /// Environment added for the process (local and netns hosts; ssh passes it with `env`).
  std::map<std::string, std::string> env;
  /// An observer (`observer: true`, the viewer): not on the roster; its failure is reported but
  /// neither ends the run nor counts in its exit code.
  bool observer = false;
};

/// Every process of one run; the clock first.
struct LaunchPlan {
  int domain_id = -1;                   ///< the DDS domain of the run, 0..232
  std::optional<std::uint64_t> run_id;  ///< given to the clock (--run-id) and everyone (CLIMBSIM_RUN_ID)
  std::vector<ProcessLaunch> processes; ///< processes[0] is the clock
};

/// Where programs named in a compose file are found.
struct ExecutableSearch {
  std::string bin_dir;      ///< <build>/bin: searched first for names without a slash
  std::string compose_dir;  ///< relative paths with a slash are relative to the compose file
  std::string path_env;     ///< the PATH to search after bin_dir (colon-separated)
};

/// Where the programs of `compose_file` are found: <build_dir>/bin, the compose file's own
/// folder (absolute), then `path_env`.
ExecutableSearch executableSearch(const std::string& compose_file, const std::string& build_dir,
                                  const std::string& path_env);

/// The program `program` resolves to: a name without a slash (climbsim-scene, the way every
/// shipped compose file names its programs) is looked up in search.bin_dir, then on
/// search.path_env; an absolute path is taken as it is; a relative path with a slash
/// (tools/my-tool, build/bin/climbsim-python) is taken from search.compose_dir, the compose
/// file's folder, wherever that file lives. Throws ConfigError, one line naming `key` (file,
/// line and service), `program` as written and the path it resolved to, if that is not an
/// executable file; if a program of that name is in search.bin_dir, the line says to name it
/// alone.
std::string resolveExecutable(const std::string& program, const std::string& key, const ExecutableSearch& search);

/// What a run with a scenario adds to the plan.
struct ScenarioRun {
  std::string scenario_file;        ///< the resolved scenario copy: ${scenario}
  std::string out_dir;              ///< the run's output directory: ${out}
  double step_ms = 5.0;             ///< replaces clock.step_ms
  double duration_s = 0.0;          ///< replaces clock.duration_s / clock.steps
  std::uint32_t depth_period = 1;   ///< `period: depth`
  std::uint32_t laser_period = 1;   ///< `period: laser`
  std::string robot_file;           ///< the scenario's robot, resolved: the clock's --robot (RunStart carries it)
};

/// The clock's and every instance's command line for a run on `domain_id` (observers get only
/// --name and --domain appended, and are not on the clock's roster), with the tokens
/// of kCommandTokens replaced and rate-named periods resolved from `scenario`. Throws
/// ConfigError if a program cannot be found, or a service needs a scenario and there is none,
/// or an offset is not below its resolved period.
///
/// With `run_id`, the clock gets --run-id and every process CLIMBSIM_RUN_ID: a participant
/// then takes no RunStart or Stop of another run (a stale one latched on a reused domain,
/// or an outsider's).
///
/// With `security_dir` (a secured run, security_material.hpp), every process gets
/// CLIMBSIM_DDS_SECURITY_DIR and its identity (the clock "clock", an instance its name).
LaunchPlan buildLaunchPlan(const ComposeFile& compose, int domain_id, const ExecutableSearch& search,
                           const std::optional<ScenarioRun>& scenario = std::nullopt,
                           std::optional<std::uint64_t> run_id = std::nullopt,
                           const std::string& security_dir = "");

/// The DDS participant name of climbsim-clockctl (what clock.control lists by default).
inline constexpr const char* kClockCtlName = "climbsim-clockctl";

/// The clock's --control-from text for `compose`: clock.control (default: climbsim-clockctl
/// from the launcher's host and the viewer observers from theirs) with each "@host"
/// replaced by its IPv4 addresses ('/'-separated; the launcher's host: every address of
/// this machine), and by "shm" if the clock runs on that host (a participant the clock
/// reaches through shared memory announces no IP address). Throws ConfigError if a named host has no address.
std::string controlSenders(const ComposeFile& compose);

/// The IPv4 addresses of this machine's interfaces (127.0.0.1 among them).
std::vector<std::string> localAddresses();

/// A random run id (never 0).
std::uint64_t randomRunId();

/// The command that runs `argv` with `env` on `host`: argv itself (local; env set by the
/// launcher), `ip netns exec NS argv` (netns), or `ssh -tt -o BatchMode=yes [ssh_options] USER@HOST --
/// 'exec env K=V ... argv'` with every word shell-quoted (ssh; the pseudo-terminal makes the
/// remote process end when the launcher ends the ssh client).
std::vector<std::string> commandOnHost(const HostSpec& host, const std::vector<std::string>& argv,
                                       const std::map<std::string, std::string>& env);

/// Checks that every used host can be started on: a netns host's namespace exists
/// (/run/netns/NAME), `ip` and `ssh` are on `path_env` where needed. Throws ConfigError
/// "<compose>:<line>: hosts.<name>.<key> = <value>: <what to do>".
void checkHosts(const ComposeFile& compose, const std::string& path_env);

/// `word` quoted for a POSIX shell ('...' with embedded quotes escaped).
std::string shellQuoted(const std::string& word);

/// The DDS discovery environment of a process on `host` of a multi-host composition
/// (climbsim/dds_discovery.hpp): every used host's address as peers, its own as interface,
/// and a peer range above the number of processes on any one host. Empty on one host.
std::map<std::string, std::string> discoveryEnvironment(const ComposeFile& compose, const HostSpec& host);

/// `value` in the shortest text that reads back to the same double ("0.1", "5", "1e-09").
std::string formatNumber(double value);

}  // namespace climbsim::launcher
