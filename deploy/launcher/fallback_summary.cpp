#include "fallback_summary.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {

namespace {
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

const char* outcomeOf(int code) {
  switch (code) {
    case kExitOk: return "completed";
    case kExitStopped: return "stopped";
    case kExitFell: return "fell";
    default: return "failed";
  }
}
}  // namespace

nlohmann::json fallbackSummary(const std::string& out_dir, const std::string& scenario_name, int launcher_exit_code,
                               const std::optional<FailedProcess>& failed) {
  std::uint64_t rows = 0;
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
    if (f_col != std::string::npos) {
      const double f = std::strtod(row[f_col].c_str(), nullptr);
      if (std::isfinite(f)) {
        f_min = std::min(f_min, f);
        f_sum += f;
        ++f_count;
      }
    }
  }
  const std::string outcome = outcomeOf(launcher_exit_code);
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
  j["exit_code"] = launcher_exit_code;
  j["steps"] = rows;
  j["sim_s"] = last_t_s;
  j["fell"] = outcome == "fell" ? nlohmann::json(true) : nlohmann::json(nullptr);
  j["min_downforce_n"] = f_count > 0 ? nlohmann::json(f_min) : nlohmann::json(nullptr);
  j["mean_downforce_n"] = f_count > 0 ? nlohmann::json(f_sum / static_cast<double>(f_count)) : nlohmann::json(nullptr);
  j["written_by"] = "launcher";
  return j;
}

bool ensureSummary(const std::string& out_dir, const std::string& scenario_name, int launcher_exit_code,
                   const std::optional<FailedProcess>& failed) {
  const std::string path = out_dir + "/summary.json";
  {
    std::ifstream in(path);
    if (in && !nlohmann::json::parse(in, nullptr, false).is_discarded()) return false;
  }
  try {
    const auto summary = fallbackSummary(out_dir, scenario_name, launcher_exit_code, failed);
    std::ofstream out(path, std::ios::trunc);
    out << summary.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write");
    spdlog::warn("the recorder wrote no summary.json: the launcher wrote {} ({} rows of trace.csv)", path,
                 summary["steps"].get<std::uint64_t>());
    return true;
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", path, e.what());
    return false;
  }
}

}  // namespace climbsim::launcher
