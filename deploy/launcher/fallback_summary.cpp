#include "fallback_summary.hpp"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
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
  j["downforce_from_s"] = hold_s;
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

std::optional<std::uint64_t> droppedSamplesIn(std::string_view line) {
  constexpr std::string_view kToken = "dropped_samples=";
  const auto at = line.find(kToken);
  if (at == std::string_view::npos) return std::nullopt;
  std::size_t end = at + kToken.size();
  std::uint64_t n = 0;
  bool any = false;
  while (end < line.size() && line[end] >= '0' && line[end] <= '9' && n < (UINT64_MAX - 9) / 10) {
    n = n * 10 + static_cast<std::uint64_t>(line[end] - '0');
    ++end;
    any = true;
  }
  return any ? std::optional<std::uint64_t>(n) : std::nullopt;
}

std::optional<WheelOverNothing> wheelOverNothingIn(std::string_view line) {
  constexpr std::string_view kWheel = "wheel ";
  constexpr std::string_view kMiddle = " stands over nothing at t = ";
  const auto middle = line.find(kMiddle);
  if (middle == std::string_view::npos) return std::nullopt;
  const auto wheel_at = line.rfind(kWheel, middle);
  if (wheel_at == std::string_view::npos) return std::nullopt;
  const std::string number(line.substr(wheel_at + kWheel.size(), middle - wheel_at - kWheel.size()));
  const std::string time(line.substr(middle + kMiddle.size(), 32));
  char* end = nullptr;
  const long wheel = std::strtol(number.c_str(), &end, 10);
  if (number.empty() || *end != '\0' || wheel < 1 || wheel > 64) return std::nullopt;
  const double at_s = std::strtod(time.c_str(), &end);
  if (end == time.c_str() || !std::isfinite(at_s)) return std::nullopt;
  return WheelOverNothing{static_cast<int>(wheel), at_s};
}

bool editSummary(const std::string& out_dir, const std::function<bool(nlohmann::json&)>& edit) {
  const std::string path = out_dir + "/summary.json";
  try {
    std::ifstream in(path);
    if (!in) return false;
    auto summary = nlohmann::json::parse(in, nullptr, false);
    in.close();
    if (summary.is_discarded() || !summary.is_object() || !edit(summary)) return false;
    std::ofstream out(path, std::ios::trunc);
    out << summary.dump(2) << "\n";
    return static_cast<bool>(out);
  } catch (const std::exception& e) {
    spdlog::error("{}: {}", path, e.what());
    return false;
  }
}

bool fillFailureReason(const std::string& out_dir, const std::string& clock_reason) {
  if (clock_reason.empty()) return false;
  return editSummary(out_dir, [&](nlohmann::json& summary) {
    const auto empty = [&](const char* key) {
      return !summary.contains(key) || !summary[key].is_string() || summary[key].get<std::string>().empty();
    };
    if (summary.value("outcome", "") != "failed" || !empty("reason")) return false;
    summary["reason"] = clock_reason;
    constexpr std::string_view kParticipant = "participant '";
    if (empty("culprit") && clock_reason.rfind(kParticipant, 0) == 0) {
      const auto end = clock_reason.find('\'', kParticipant.size());
      if (end != std::string::npos) summary["culprit"] = clock_reason.substr(kParticipant.size(), end - kParticipant.size());
    }
    return true;
  });
}

void addWheelsOverNothing(const std::string& out_dir, const std::vector<WheelOverNothing>& wheels) {
  editSummary(out_dir, [&](nlohmann::json& summary) {
    if (wheels.empty()) {
      summary["wheels_over_nothing"] = nullptr;
      return true;
    }
    double first = wheels.front().at_s;
    nlohmann::json numbers = nlohmann::json::array();
    for (const auto& w : wheels) {
      first = std::min(first, w.at_s);
      if (std::find(numbers.begin(), numbers.end(), w.wheel) == numbers.end()) numbers.push_back(w.wheel);
    }
    summary["wheels_over_nothing"] = {{"first_at_s", first}, {"wheels", numbers}};
    return true;
  });
}

void addDroppedSamples(const std::string& out_dir, const std::map<std::string, std::uint64_t>& by_service) {
  std::uint64_t total = 0;
  const bool written = editSummary(out_dir, [&](nlohmann::json& summary) {
    std::uint64_t own = summary.contains("dropped_samples") && summary["dropped_samples"].is_number_unsigned()
                            ? summary["dropped_samples"].get<std::uint64_t>()
                            : 0;
    if (summary.contains("dropped_samples_by_service")) own = summary["dropped_samples_by_service"].value("recorder", own);
    nlohmann::json each = nlohmann::json::object();
    each["recorder"] = own;
    total = own;
    for (const auto& [service, n] : by_service) {
      if (service == "recorder") continue;
      each[service] = n;
      total += n;
    }
    summary["dropped_samples"] = total;
    summary["dropped_samples_by_service"] = each;
    return true;
  });
  if (written && total > 0) {
    spdlog::warn("the services dropped {} samples in all (summary.json dropped_samples_by_service)", total);
  }
}

}  // namespace climbsim::launcher
