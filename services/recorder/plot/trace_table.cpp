#include "trace_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "climbsim/errors.hpp"

namespace climbsim::plot {
namespace {

std::vector<std::string> splitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::stringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
  std::size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  return s.substr(i);
}

}  // namespace

TraceTable TraceTable::read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot read the trace (missing? a run directory holds trace.csv)");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

TraceTable TraceTable::parse(const std::string& text, const std::string& source) {
  TraceTable t;
  t.source_ = source;
  std::stringstream in(text);
  std::string line;
  std::size_t line_no = 0;
  if (!std::getline(in, line)) throw ConfigError(source + ":1: empty file: no header line");
  ++line_no;
  for (auto& name : splitCells(line)) t.names_.push_back(trimmed(name));
  for (std::size_t c = 0; c < t.names_.size(); ++c) {
    if (t.names_[c].empty()) {
      throw ConfigError(source + ":1: column " + std::to_string(c + 1) + ": empty column name in the header");
    }
  }
  t.columns_.resize(t.names_.size());
  while (std::getline(in, line)) {
    ++line_no;
    if (trimmed(line).empty()) continue;
    const auto cells = splitCells(line);
    if (cells.size() != t.names_.size()) {
      throw ConfigError(source + ":" + std::to_string(line_no) + ": " + std::to_string(cells.size()) +
                        " cells, the header has " + std::to_string(t.names_.size()));
    }
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string cell = trimmed(cells[c]);
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size()) {
        throw ConfigError(source + ":" + std::to_string(line_no) + ": column " + t.names_[c] + " = '" + cell +
                          "': not a number");
      }
      t.columns_[c].push_back(v);
    }
    ++t.rows_;
  }
  return t;
}

bool TraceTable::has(const std::string& name) const {
  for (const auto& n : names_) {
    if (n == name) return true;
  }
  return false;
}

const std::vector<double>& TraceTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < names_.size(); ++c) {
    if (names_[c] == name) return columns_[c];
  }
  std::string header;
  for (const auto& n : names_) header += (header.empty() ? "" : ",") + n;
  if (header.size() > 120) header = header.substr(0, 117) + "...";
  throw ConfigError(source_ + ":1: no column '" + name + "' (header: " + header + ")");
}

std::size_t TraceTable::rowNearest(double t_s) const {
  if (rows_ == 0) throw ConfigError(source_ + ": no rows (the run recorded no step)");
  const auto& t = column("t_s");
  std::size_t best = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (std::abs(t[i] - t_s) < std::abs(t[best] - t_s)) best = i;
  }
  return best;
}

}  // namespace climbsim::plot
