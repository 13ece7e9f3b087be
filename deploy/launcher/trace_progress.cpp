#include "trace_progress.hpp"

#include "climbsim/realtime_text.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace climbsim::launcher {

namespace {
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) {
    out.push_back(cell);
  }
  return out;
}

std::optional<double> parsed(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}
}  // namespace

void TraceTail::takeLine(const std::string& line) {
  if (header_.empty()) {
    header_ = cells(line);
    for (std::size_t i = 0; i < header_.size(); ++i) {
      if (header_[i] == "t_s") t_column_ = static_cast<int>(i);
      if (header_[i] == "downforce_n") downforce_column_ = static_cast<int>(i);
    }
    return;
  }
  if (t_column_ < 0) return;
  const auto row = cells(line);
  if (row.size() != header_.size()) return;
  const auto t = parsed(row[static_cast<std::size_t>(t_column_)]);
  if (!t) return;
  TraceSample sample;
  sample.t_s = *t;
  if (downforce_column_ >= 0) sample.downforce_n = parsed(row[static_cast<std::size_t>(downforce_column_)]);
  sample.rows = ++rows_;
  last_ = sample;
}

std::optional<TraceSample> TraceTail::poll() {
  std::ifstream in(path_, std::ios::binary);
  if (!in) return last_;
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  if (size < offset_) {  // a new file (a new run): start over
    offset_ = 0;
    partial_.clear();
    header_.clear();
    t_column_ = downforce_column_ = -1;
    last_.reset();
    rows_ = 0;
  }
  if (size == offset_) return last_;
  in.seekg(static_cast<std::streamoff>(offset_));
  std::string chunk(size - offset_, '\0');
  in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
  chunk.resize(static_cast<std::size_t>(in.gcount()));
  offset_ += chunk.size();
  partial_ += chunk;
  std::size_t begin = 0;
  for (std::size_t end = partial_.find('\n'); end != std::string::npos; end = partial_.find('\n', begin)) {
    takeLine(partial_.substr(begin, end - begin));
    begin = end + 1;
  }
  partial_.erase(0, begin);
  return last_;
}

void RateMeter::see(double wall_s, double t_s) {
  if (!first_) first_ = std::make_pair(wall_s, t_s);
  if (!last_ || t_s > last_->second) last_ = std::make_pair(wall_s, t_s);
}

std::optional<double> RateMeter::rate(double now_wall_s, bool ended) const {
  if (!first_) return std::nullopt;
  const double until_s = ended ? last_->first : now_wall_s;
  const double wall_s = until_s - first_->first;
  if (!(wall_s > 0.2)) return std::nullopt;
  return (last_->second - first_->second) / wall_s;
}

std::string progressText(const std::optional<TraceSample>& sample, double duration_s, std::optional<double> rtf,
                         const std::string& state) {
  char buffer[160];
  std::string text;
  if (!sample) {
    text = "t -";
  } else if (duration_s > 0.0) {
    std::snprintf(buffer, sizeof(buffer), "t %.2f/%g s (%.0f%%)", sample->t_s, duration_s,
                  100.0 * sample->t_s / duration_s);
    text = buffer;
  } else {
    std::snprintf(buffer, sizeof(buffer), "t %.2f s", sample->t_s);
    text = buffer;
  }
  if (rtf) text += "  " + realtimeText(*rtf);  // "0.017x" for a short run, not "0.0x"
  if (sample && sample->downforce_n) {
    std::snprintf(buffer, sizeof(buffer), "  F %.0f N", *sample->downforce_n);
    text += buffer;
  }
  return text + "  " + state;
}

}  // namespace climbsim::launcher
