#pragma once
/// @file
/// What summary.json learns from the services' output lines after the recorder wrote it: the
/// wheels the drive found over nothing, what each service dropped, the clock's reason for a
/// failure the recorder did not see. The launcher adds them from the lines; climbsim solo
/// adds the wheels from the same lines of its drive.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace climbsim::run_summary {

/// A wheel the drive found over nothing (no scene surface under its contact point).
struct WheelOverNothing {
  int wheel = 0;      ///< 1-based
  double at_s = 0.0;  ///< simulation time [s]
};

/// The wheel and time of a drive's "wheel N stands over nothing at t = T s" output line.
std::optional<WheelOverNothing> wheelOverNothingIn(std::string_view line);

/// summary.json's wheels_over_nothing: null when `wheels` is empty, else {first_at_s, wheels:
/// [N, ...] (each once, in the order they left the scene)}.
nlohmann::json wheelsOverNothingJson(const std::vector<WheelOverNothing>& wheels);

/// Sets out_dir/summary.json's wheels_over_nothing (wheelsOverNothingJson). Nothing if there
/// is no summary.json; never throws.
void addWheelsOverNothing(const std::string& out_dir, const std::vector<WheelOverNothing>& wheels);

/// The N of a service's "dropped_samples=N" output line (common run_stats.hpp
/// logDroppedSamples), if the line has one.
std::optional<std::uint64_t> droppedSamplesIn(std::string_view line);

/// Adds what every service dropped to out_dir/summary.json: dropped_samples becomes the
/// recorder's own count (the summary's value) plus the services', dropped_samples_by_service
/// lists each (the recorder's own under "recorder"). Nothing if there is no summary.json;
/// never throws (a failure is logged).
void addDroppedSamples(const std::string& out_dir, const std::map<std::string, std::uint64_t>& by_service);

/// Fills an empty `reason` of a failed run's out_dir/summary.json (the recorder saw the clock
/// vanish before any Stop came) with the clock's own failure `clock_reason` ("run failed: ..."
/// in its output), and an empty `culprit` with the participant it names first ("participant
/// 'x' ..."). Returns whether it changed the file; never throws.
bool fillFailureReason(const std::string& out_dir, const std::string& clock_reason);

}  // namespace climbsim::run_summary
