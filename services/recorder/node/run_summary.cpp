#include "node/run_summary.hpp"

namespace climbsim::recorder {

nlohmann::json runSummary(const TraceRecorder& recorder, const std::string& label, double wall_s,
                          const std::string& outcome, const std::string& reason, const std::string& culprit,
                          int exit_code) {
  nlohmann::json summary = recorder.summary();
  summary["scenario"] = label;
  summary["wall_s"] = wall_s;
  summary["realtime_factor"] = wall_s > 0.0 ? summary["sim_s"].get<double>() / wall_s : 0.0;
  if (outcome == "fell") {
    // The drive's fall ended the run; the trace may end before a row holds the fallen state
    // (the recorder reads stamps < k, and the clock may freeze the horizon right after the
    // fall's step), but the run fell all the same.
    summary["fell"] = true;
    summary["adhesion_failed"] = true;
  }
  summary["outcome"] = outcome;
  summary["reason"] = reason;
  summary["culprit"] = culprit;
  summary["completed"] = outcome == "completed";
  summary["exit_code"] = exit_code;
  return summary;
}

}  // namespace climbsim::recorder
