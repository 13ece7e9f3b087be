#include "climbsim/grid_record.hpp"

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"

namespace climbsim {

std::string gridRecordPath(const std::string& run_dir) {
  return (std::filesystem::path(run_dir) / "viewer" / "depth_grids.jsonl").string();
}

GridRecorder::GridRecorder(const std::string& path, std::int64_t interval_ns) : interval_ns_(interval_ns) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  out_.open(path, std::ios::trunc);
  if (!out_) throw ConfigError(path + ": cannot write the depth grids");
}

bool GridRecorder::offer(std::int64_t t_ns, const std::string& json_line) {
  if (any_ && t_ns < last_t_ns_ + interval_ns_) return false;
  out_ << json_line << '\n';
  out_.flush();
  last_t_ns_ = t_ns;
  any_ = true;
  return true;
}

std::vector<std::pair<double, std::string>> loadGridRecords(const std::string& path) {
  std::vector<std::pair<double, std::string>> records;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const auto message = nlohmann::json::parse(line, nullptr, false);
    if (message.is_discarded() || !message.is_object() || message.value("type", "") != "depth" ||
        !message.contains("t_s") || !message["t_s"].is_number()) {
      continue;
    }
    records.emplace_back(message["t_s"].get<double>(), line);
  }
  return records;
}

const std::string& gridAt(const std::vector<std::pair<double, std::string>>& records, double t_s) {
  static const std::string kNone;
  if (records.empty()) return kNone;
  const auto after = std::upper_bound(records.begin(), records.end(), t_s,
                                      [](double t, const auto& record) { return t < record.first; });
  return after == records.begin() ? records.front().second : std::prev(after)->second;
}

}  // namespace climbsim
