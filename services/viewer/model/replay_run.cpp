#include "replay_run.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::viewer {

namespace {
std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

bool parseNumber(const std::string& cell, double& value) {
  if (cell.empty()) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(cell.c_str(), &end);
  return errno == 0 && end == cell.c_str() + cell.size();
}
}  // namespace

nlohmann::json loadTraceColumns(const std::string& trace_csv) {
  std::ifstream in(trace_csv);
  if (!in) throw ConfigError(trace_csv + ": cannot read the trace (no trace.csv: is this a run directory?)");
  std::string line;
  if (!std::getline(in, line) || line.empty()) throw ConfigError(trace_csv + ":1: empty file: no header");
  const std::vector<std::string> names = splitCommas(line);
  std::vector<std::vector<double>> values(names.size());
  int line_number = 1;
  std::string next;
  bool have_next = static_cast<bool>(std::getline(in, next));
  while (have_next) {
    line = std::move(next);
    ++line_number;
    have_next = static_cast<bool>(std::getline(in, next));
    const bool last = !have_next;
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitCommas(line);
    std::vector<double> row(cells.size());
    bool ok = cells.size() == names.size();
    std::size_t bad = cells.size();
    for (std::size_t i = 0; ok && i < cells.size(); ++i) {
      if (!parseNumber(cells[i], row[i])) {
        ok = false;
        bad = i;
      }
    }
    if (!ok) {
      if (last) break;  // cut off while the run was writing it
      const std::string where = trace_csv + ":" + std::to_string(line_number) + ": ";
      if (cells.size() != names.size()) {
        throw ConfigError(where + "row has " + std::to_string(cells.size()) + " cells, the header " +
                          std::to_string(names.size()));
      }
      throw ConfigError(where + "column " + names[bad] + " = " + cells[bad] + ": not a number");
    }
    for (std::size_t i = 0; i < row.size(); ++i) values[i].push_back(row[i]);
  }
  return {{"columns", names}, {"values", values}};
}

nlohmann::json listSealingPictures(const std::string& run_dir) {
  namespace fs = std::filesystem;
  nlohmann::json out = nlohmann::json::array();
  const fs::path dir = fs::path(run_dir) / "pictures";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  std::vector<std::tuple<double, std::string, std::string>> found;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    for (const std::string kind : {"edges", "gaps"}) {
      const std::string prefix = "sealing_" + kind + "_";
      if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() + 5 &&
          name.compare(name.size() - 5, 5, "s.png") == 0) {
        double t_s = 0.0;
        if (parseNumber(name.substr(prefix.size(), name.size() - prefix.size() - 5), t_s)) {
          found.emplace_back(t_s, kind, "pictures/" + name);
        }
      }
    }
  }
  std::sort(found.begin(), found.end());
  for (const auto& [t_s, kind, file] : found) out.push_back({{"kind", kind}, {"t_s", t_s}, {"file", file}});
  return out;
}

}  // namespace climbsim::viewer
