#pragma once
/// @file
/// summary.json of a run directory (docs/scenario-files.md), shared by climbsim-recorder and the
/// in-process run (climbsim solo) so that both write the same keys.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "node/trace_recorder.hpp"

namespace climbsim::recorder {

/// The T [s] of a reason "... FELL at t = T s ...", if it has one.
std::optional<double> fellAtInReason(const std::string& reason);

/// TraceRecorder::summary() with the run's label (`scenario`), wall time `wall_s` [s] and
/// realtime_factor = sim_s / wall_s (0 without wall time), and how the run ended: `outcome`
/// (completed, stopped, fell, failed), the Stop's `reason` and `culprit`, `completed`
/// (outcome == completed) and the run's `exit_code`. An outcome "fell" also sets `fell` and
/// `adhesion_failed`, whether or not a row of the trace already holds the fallen state, and a
/// `fell_at_s` that no row gave from the reason ("FELL at t = 2.105 s: ...", the drive's:
/// the end of the step that found the fall, the time of the first row that would hold it).
nlohmann::json runSummary(const TraceRecorder& recorder, const std::string& label, double wall_s,
                          const std::string& outcome, const std::string& reason, const std::string& culprit,
                          int exit_code);

}  // namespace climbsim::recorder
