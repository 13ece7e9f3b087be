#pragma once
/// @file
/// Runs side by side: every `run`/`up` has a run name, and with it its own run directory
/// <build>/run/<name>/ (state.json, logs, supervisor.lock). This file names runs, finds the
/// runs of a build directory and picks the one a `ps`, `logs` or `down` means.

#include <optional>
#include <string>
#include <vector>

#include "file_lock.hpp"
#include "run_state.hpp"

namespace climbsim::launcher {

/// Throws ConfigError "--name NAME: ..." unless `name` is 1..63 of [A-Za-z0-9_.-], not only dots.
void validateRunName(const std::string& name);

/// The default run name: `base` (a scenario's name or file stem, or the compose file's name)
/// with every character outside [A-Za-z0-9_.-] replaced by '-' and cut to leave room for a
/// "-N" suffix; "run" if nothing is left.
std::string baseRunName(const std::string& base);

/// The run name and the held lock of a new run.
struct ClaimedRun {
  std::string name;
  RunPaths paths;
  FileLock lock;
};

/// Takes the run directory of a new run. `explicit_name`: exactly that name, nothing if a run
/// of that name is running. Else `base`, `base-2`, `base-3`, ...: the first whose lock is free
/// (a name is unique among the runs running now; a finished run's directory is reused).
std::optional<ClaimedRun> claimRun(const std::string& build_dir, const std::string& base, bool explicit_name);

/// A run directory of a build and what is known of it.
struct RunEntry {
  std::string name;
  RunPaths paths;
  bool running = false;           ///< its supervisor holds the lock
  std::optional<RunState> state;  ///< state.json, if readable
};

/// Every run directory under <build>/run, running ones first, then by start time (newest
/// first), then by name.
std::vector<RunEntry> listRuns(const std::string& build_dir);

/// The run `name` names, or (empty `name`) the only running run; with none running, the most
/// recently started run if `allow_finished`. `compose_file` (absolute, or empty) keeps only
/// runs of that compose file. Throws ConfigError with one line saying which runs there are
/// when the choice is ambiguous or the name unknown; nothing when there is no run at all.
std::optional<RunEntry> selectRun(const std::string& build_dir, const std::string& name,
                                  const std::string& compose_file, bool allow_finished);

}  // namespace climbsim::launcher
