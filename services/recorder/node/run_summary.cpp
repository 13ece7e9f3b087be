#include "node/run_summary.hpp"

#include <cmath>
#include <cstdlib>

namespace climbsim::recorder {

std::optional<double> fellAtInReason(const std::string& reason) {
  constexpr const char* kFell = "FELL at t = ";
  const auto at = reason.find(kFell);
  if (at == std::string::npos) return std::nullopt;
  const char* begin = reason.c_str() + at + std::char_traits<char>::length(kFell);
  char* end = nullptr;
  const double t_s = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(t_s) || t_s < 0.0) return std::nullopt;
  return t_s;
}

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
    // fall's step), but the run fell all the same, at the time its reason gives.
    summary["fell"] = true;
    summary["adhesion_failed"] = true;
    if (summary["fell_at_s"].is_null()) {
      if (const auto t_s = fellAtInReason(reason)) summary["fell_at_s"] = *t_s;
    }
  }
  summary["outcome"] = outcome;
  summary["reason"] = reason;
  summary["culprit"] = culprit;
  summary["completed"] = outcome == "completed";
  summary["exit_code"] = exit_code;
  return summary;
}

}  // namespace climbsim::recorder
