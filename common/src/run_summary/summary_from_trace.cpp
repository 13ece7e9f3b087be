#include "climbsim/run_summary/summary_from_trace.hpp"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "climbsim/run_summary/run_summary.hpp"

namespace climbsim::run_summary {

namespace {
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

/// start.hold_s of the run directory's scenario.yaml (the launcher's resolved copy), 0 if it
/// has none or does not read: the downforce statistics start there, as the recorder's.
double holdEndS(const std::string& out_dir) {
  try {
    const YAML::Node scenario = YAML::LoadFile(out_dir + "/scenario.yaml");
    const double hold_s = scenario["start"]["hold_s"].as<double>(0.0);
    return std::isfinite(hold_s) && hold_s > 0.0 ? hold_s : 0.0;
  } catch (const std::exception&) {
    return 0.0;
  }
}
}  // namespace

nlohmann::json summaryFromTrace(const std::string& out_dir, const std::string& scenario_name, int exit_code,
                                const std::optional<FailedProcess>& failed) {
  std::uint64_t rows = 0;
  const double hold_s = holdEndS(out_dir);
  const auto from_ns = std::llround(hold_s * 1e9);
  double last_t_s = 0.0, f_min = INFINITY, f_sum = 0.0;
  std::uint64_t f_count = 0;
  std::ifstream trace(out_dir + "/trace.csv");
  std::string line;
  std::size_t t_col = 0, f_col = std::string::npos, columns = 0;
  if (std::getline(trace, line)) {
    const auto header = cells(line);
    columns = header.size();
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == "t_s") t_col = i;
      if (header[i] == "downforce_n") f_col = i;
    }
  }
  while (std::getline(trace, line)) {
    const auto row = cells(line);
    if (row.size() != columns || columns == 0) break;  // a row cut off when the recorder died
    ++rows;
    last_t_s = std::strtod(row[t_col].c_str(), nullptr);
    if (f_col != std::string::npos && std::llround(last_t_s * 1e9) >= from_ns) {
      const double f = std::strtod(row[f_col].c_str(), nullptr);
      if (std::isfinite(f)) {
        f_min = std::min(f_min, f);
        f_sum += f;
        ++f_count;
      }
    }
  }
  const std::string outcome = outcomeOfExitCode(exit_code);
  std::string reason = "the recorder wrote no summary.json";
  if (failed) {
    reason = "service '" + failed->name + "' exited with code " + std::to_string(failed->exit_code) + "; " + reason;
  }
  reason += " (this one is the launcher's, from the " + std::to_string(rows) + " rows of trace.csv)";
  nlohmann::json j;
  j["scenario"] = scenario_name;
  j["outcome"] = outcome;
  j["reason"] = reason;
  j["culprit"] = failed ? failed->name : std::string();
  j["completed"] = outcome == "completed";
  j["exit_code"] = exit_code;
  j["steps"] = rows;
  j["sim_s"] = last_t_s;
  j["fell"] = outcome == "fell" ? nlohmann::json(true) : nlohmann::json(nullptr);
  j["downforce_from_s"] = hold_s;
  j["min_downforce_n"] = f_count > 0 ? nlohmann::json(f_min) : nlohmann::json(nullptr);
  j["mean_downforce_n"] = f_count > 0 ? nlohmann::json(f_sum / static_cast<double>(f_count)) : nlohmann::json(nullptr);
  j["written_by"] = "launcher";
  return j;
}

bool ensureSummary(const std::string& out_dir, const std::string& scenario_name, int exit_code,
                   const std::optional<FailedProcess>& failed) {
  if (hasSummary(out_dir)) return false;
  const std::string path = summaryPath(out_dir);
  try {
    const auto summary = summaryFromTrace(out_dir, scenario_name, exit_code, failed);
    if (!writeSummary(out_dir, summary)) throw std::runtime_error("cannot write");
    spdlog::warn("the recorder wrote no summary.json: the launcher wrote {} ({} rows of trace.csv)", path,
                 summary["steps"].get<std::uint64_t>());
    return true;
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", path, e.what());
    return false;
  }
}

}  // namespace climbsim::run_summary
