#pragma once
/// @file
/// summary.json when the recorder could not write it (it was killed, or crashed): the launcher
/// writes one for any outcome, from what is on disk. Every row the recorder wrote stays in
/// trace.csv (it flushes rows within 20 ms); this summary is computed from those rows, so nothing
/// already computed is lost, and it says that the recorder did not finish.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace climbsim::launcher {

/// A process that failed: its name and exit code (128 + signal for a signal).
struct FailedProcess {
  std::string name;
  int exit_code = 0;
};

/// The summary of a run directory whose recorder wrote none: `outcome` and `exit_code` from the
/// launcher's exit code (0 completed, 4 stopped, 5 fell, else failed; completed only for 0),
/// `reason` and `culprit` from `failed` (the first service that failed), and from trace.csv:
/// steps (rows), sim_s (the last row's t_s), min_downforce_n and mean_downforce_n (over the
/// finite values of downforce_n; null if none). `written_by: "launcher"`. fell is null (the
/// recorder's knowledge of it is gone) unless the outcome says so.
nlohmann::json fallbackSummary(const std::string& out_dir, const std::string& scenario_name, int launcher_exit_code,
                               const std::optional<FailedProcess>& failed);

/// Writes fallbackSummary() to out_dir/summary.json unless that file exists and holds JSON;
/// returns whether it wrote one. Never throws (a failure to write is logged).
bool ensureSummary(const std::string& out_dir, const std::string& scenario_name, int launcher_exit_code,
                   const std::optional<FailedProcess>& failed);

/// The N of a service's "dropped_samples=N" output line (common run_stats.hpp
/// logDroppedSamples), if the line has one.
std::optional<std::uint64_t> droppedSamplesIn(std::string_view line);

/// A wheel the drive found over nothing (no scene surface under its contact point).
struct WheelOverNothing {
  int wheel = 0;      ///< 1-based
  double at_s = 0.0;  ///< simulation time [s]
};

/// The wheel and time of a drive's "wheel N stands over nothing at t = T s" output line.
std::optional<WheelOverNothing> wheelOverNothingIn(std::string_view line);

/// Sets out_dir/summary.json's wheels_over_nothing: null when `wheels` is empty, else
/// {first_at_s, wheels: [N, ...] (in the order they left the scene)}. Nothing if there is no
/// summary.json; never throws.
void addWheelsOverNothing(const std::string& out_dir, const std::vector<WheelOverNothing>& wheels);

/// Reads out_dir/summary.json, lets `edit` change it and writes it back if `edit` returns
/// true. Returns whether it wrote: false if there is no summary.json, it holds no JSON object,
/// `edit` declined, or writing failed (logged). Never throws.
bool editSummary(const std::string& out_dir, const std::function<bool(nlohmann::json&)>& edit);

/// Fills an empty `reason` of a failed run's out_dir/summary.json (the recorder saw the clock
/// vanish before any Stop came) with the clock's own failure `clock_reason` ("run failed: ..."
/// in its output), and an empty `culprit` with the participant it names first ("participant
/// 'x' ..."). Returns whether it changed the file; never throws.
bool fillFailureReason(const std::string& out_dir, const std::string& clock_reason);

/// Adds what every service dropped to out_dir/summary.json: dropped_samples becomes the
/// recorder's own count (the summary's value) plus the services', dropped_samples_by_service
/// lists each (the recorder's own under "recorder"). Nothing if there is no summary.json;
/// never throws (a failure is logged).
void addDroppedSamples(const std::string& out_dir, const std::map<std::string, std::uint64_t>& by_service);

}  // namespace climbsim::launcher
