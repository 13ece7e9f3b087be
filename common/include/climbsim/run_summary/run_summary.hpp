#pragma once
/// @file
/// summary.json of a run directory (docs/scenario-files.md): what the recorder, climbsim solo
/// and, when the recorder wrote none, the launcher write there. This library is the file's one
/// writer (writeSummary, editSummary): every run gives the same keys whoever wrote them.

#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace climbsim::run_summary {

/// How a run ended, as the clock's Stop (or the launcher's exit code) says it.
struct RunEnd {
  std::string outcome;  ///< completed, stopped, fell or failed
  std::string reason;   ///< the Stop's reason
  std::string culprit;  ///< the participant that ended the run ("" for none)
  int exit_code = 0;    ///< the run's exit code (ExitCode: 0, kExitStopped, kExitFell, kExitFailed)
};

/// The outcome of a run's exit code: completed (kExitOk), stopped (kExitStopped), fell
/// (kExitFell), else failed.
const char* outcomeOfExitCode(int exit_code);

/// The T [s] of a reason "... FELL at t = T s ...", if it has one.
std::optional<double> fellAtInReason(const std::string& reason);

/// The summary of a run: the trace's statistics (`trace_summary`: TraceRecorder::summary())
/// with the run's label (`scenario`), wall time `wall_s` [s] and realtime_factor = sim_s /
/// wall_s (0 without wall time), and how the run ended: `outcome`, `reason`, `culprit`,
/// `completed` (outcome == completed) and `exit_code`. An outcome "fell" also sets `fell` and
/// `adhesion_failed`, whether or not a row of the trace already holds the fallen state, and a
/// `fell_at_s` that no row gave from the reason ("FELL at t = 2.105 s: ...", the drive's: the
/// end of the step that found the fall, the time of the first row that would hold it).
nlohmann::json runSummary(nlohmann::json trace_summary, const std::string& label, double wall_s, const RunEnd& end);

/// out_dir/summary.json.
std::string summaryPath(const std::string& out_dir);

/// Writes `summary` to out_dir/summary.json (2-space indented, a final newline); whether it
/// could.
bool writeSummary(const std::string& out_dir, const nlohmann::json& summary);

/// Reads out_dir/summary.json, lets `edit` change it and writes it back if `edit` returns
/// true. Returns whether it wrote: false if there is no summary.json, it holds no JSON object,
/// `edit` declined, or writing failed (logged). Never throws.
bool editSummary(const std::string& out_dir, const std::function<bool(nlohmann::json&)>& edit);

/// Whether out_dir/summary.json exists and holds JSON.
bool hasSummary(const std::string& out_dir);

/// For a summary whose robot stayed on the wall but slid beyond the scenario's limit (`slid`
/// and not `fell`): "the robot slid 264 mm, beyond the scenario's slide_limit_m of 5 mm
/// (adhesion failed)", the words a run's final line adds to "completed". Empty otherwise.
std::string slideBeyondLimit(const nlohmann::json& summary);

/// slideBeyondLimit of out_dir/summary.json; empty if there is none.
std::string slideBeyondLimitOf(const std::string& out_dir);

}  // namespace climbsim::run_summary
