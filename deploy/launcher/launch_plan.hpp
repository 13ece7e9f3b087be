#pragma once
/// @file
/// From a compose file to the command lines of one run: the clock with its roster, and
/// every service instance with --name, --period, --offset and --domain appended.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "compose_file.hpp"

namespace climbsim::launcher {

/// One process to start.
struct ProcessLaunch {
  std::string name;               ///< "clock" or a roster name (log file, prefix, `ps`)
  std::vector<std::string> argv;  ///< argv[0] is an absolute path or a name found on PATH
};

/// Every process of one run; the clock first.
struct LaunchPlan {
  int domain_id = -1;                   ///< the DDS domain of the run, 0..232
  std::vector<ProcessLaunch> processes; ///< processes[0] is the clock
};

/// Where programs named in a compose file are found.
struct ExecutableSearch {
  std::string bin_dir;      ///< <build>/bin: searched first for names without a slash
  std::string compose_dir;  ///< relative paths with a slash are relative to the compose file
  std::string path_env;     ///< the PATH to search after bin_dir (colon-separated)
};

/// The program `program` resolves to: a name without a slash is looked up in
/// search.bin_dir, then on search.path_env; a relative path with a slash is taken relative
/// to search.compose_dir. Throws ConfigError naming `key` and `program` if it is not an
/// executable file.
std::string resolveExecutable(const std::string& program, const std::string& key, const ExecutableSearch& search);

/// What a run with a scenario adds to the plan.
struct ScenarioRun {
  std::string scenario_file;        ///< the resolved scenario copy: ${scenario}
  std::string out_dir;              ///< the run's output directory: ${out}
  double step_ms = 5.0;             ///< replaces clock.step_ms
  double duration_s = 0.0;          ///< replaces clock.duration_s / clock.steps
  std::uint32_t depth_period = 1;   ///< `period: depth`
  std::uint32_t laser_period = 1;   ///< `period: laser`
};

/// The clock's and every instance's command line for a run on `domain_id`, with the tokens
/// of kCommandTokens replaced and rate-named periods resolved from `scenario`. Throws
/// ConfigError if a program cannot be found, or a service needs a scenario and there is none,
/// or an offset is not below its resolved period.
LaunchPlan buildLaunchPlan(const ComposeFile& compose, int domain_id, const ExecutableSearch& search,
                           const std::optional<ScenarioRun>& scenario = std::nullopt);

/// `value` in the shortest text that reads back to the same double ("0.1", "5", "1e-09").
std::string formatNumber(double value);

}  // namespace climbsim::launcher
