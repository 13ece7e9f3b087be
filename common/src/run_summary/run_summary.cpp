#include "climbsim/run_summary/run_summary.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "climbsim/errors.hpp"

namespace climbsim::run_summary {

const char* outcomeOfExitCode(int exit_code) {
  switch (exit_code) {
    case kExitOk: return "completed";
    case kExitStopped: return "stopped";
    case kExitFell: return "fell";
    default: return "failed";
  }
}

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

nlohmann::json runSummary(nlohmann::json trace_summary, const std::string& label, double wall_s, const RunEnd& end) {
  nlohmann::json summary = std::move(trace_summary);
  summary["scenario"] = label;
  summary["wall_s"] = wall_s;
  summary["realtime_factor"] = wall_s > 0.0 ? summary["sim_s"].get<double>() / wall_s : 0.0;
  if (end.outcome == "fell") {
    // The drive's fall ended the run; the trace may end before a row holds the fallen state
    // (the recorder reads stamps < k, and the clock may freeze the horizon right after the
    // fall's step), but the run fell all the same, at the time its reason gives.
    summary["fell"] = true;
    summary["adhesion_failed"] = true;
    if (summary["fell_at_s"].is_null()) {
      if (const auto t_s = fellAtInReason(end.reason)) summary["fell_at_s"] = *t_s;
    }
  }
  summary["outcome"] = end.outcome;
  summary["reason"] = end.reason;
  summary["culprit"] = end.culprit;
  summary["completed"] = end.outcome == "completed";
  summary["exit_code"] = end.exit_code;
  return summary;
}

std::string summaryPath(const std::string& out_dir) { return out_dir + "/summary.json"; }

bool writeSummary(const std::string& out_dir, const nlohmann::json& summary) {
  std::ofstream out(summaryPath(out_dir), std::ios::trunc);
  out << summary.dump(2) << "\n";
  return static_cast<bool>(out);
}

bool editSummary(const std::string& out_dir, const std::function<bool(nlohmann::json&)>& edit) {
  const std::string path = summaryPath(out_dir);
  try {
    std::ifstream in(path);
    if (!in) return false;
    auto summary = nlohmann::json::parse(in, nullptr, false);
    in.close();
    if (summary.is_discarded() || !summary.is_object() || !edit(summary)) return false;
    return writeSummary(out_dir, summary);
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", path, e.what());
    return false;
  }
}

bool hasSummary(const std::string& out_dir) {
  std::ifstream in(summaryPath(out_dir));
  return in && !nlohmann::json::parse(in, nullptr, false).is_discarded();
}

namespace {
/// "264 mm", "1.89 mm": three significant digits.
std::string millimetres(double metres) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.3g mm", metres * 1e3);
  return text;
}
}  // namespace

std::string slideBeyondLimit(const nlohmann::json& summary) {
  if (!summary.is_object() || !summary.value("slid", false) || summary.value("fell", false)) return {};
  const auto number = [&](const char* key) {
    const auto it = summary.find(key);
    return it != summary.end() && it->is_number() ? it->get<double>() : std::nan("");
  };
  return "the robot slid " + millimetres(number("slide_m")) + ", beyond the scenario's slide_limit_m of " +
         millimetres(number("slide_limit_m")) + " (adhesion failed)";
}

std::string slideBeyondLimitOf(const std::string& out_dir) {
  std::ifstream in(summaryPath(out_dir));
  if (!in) return {};
  return slideBeyondLimit(nlohmann::json::parse(in, nullptr, false));
}

}  // namespace climbsim::run_summary
