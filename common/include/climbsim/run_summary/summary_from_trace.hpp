#pragma once
/// @file
/// summary.json when the recorder could not write it (it was killed, or crashed): the launcher
/// writes one for any outcome, from what is on disk. Every row the recorder wrote stays in
/// trace.csv (it flushes rows within 20 ms); this summary is computed from those rows, so nothing
/// already computed is lost, and it says that the recorder did not finish.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace climbsim::run_summary {

/// A process that failed: its name and exit code (128 + signal for a signal).
struct FailedProcess {
  std::string name;
  int exit_code = 0;
};

/// The summary of a run directory whose recorder wrote none: `outcome` and `exit_code` from the
/// run's exit code (outcomeOfExitCode), `reason` and `culprit` from `failed` (the first service
/// that failed), and from trace.csv: steps (rows), sim_s (the last row's t_s), min_downforce_n
/// and mean_downforce_n (over the finite values of downforce_n from the run's start.hold_s on,
/// as the recorder's; null if none). `written_by: "launcher"`. fell is null (the recorder's
/// knowledge of it is gone) unless the outcome says so.
nlohmann::json summaryFromTrace(const std::string& out_dir, const std::string& scenario_name, int exit_code,
                                const std::optional<FailedProcess>& failed);

/// Writes summaryFromTrace() to out_dir/summary.json unless that file exists and holds JSON;
/// returns whether it wrote one. Never throws (a failure to write is logged).
bool ensureSummary(const std::string& out_dir, const std::string& scenario_name, int exit_code,
                   const std::optional<FailedProcess>& failed);

}  // namespace climbsim::run_summary
