#include "climbsim/leakage_merger.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace climbsim {
namespace {

std::string fmt(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

}  // namespace

LeakageMerger::LeakageMerger(std::vector<std::string> segment_names, std::vector<double> initial_leak_area_m2)
    : names_(std::move(segment_names)), leak_area_m2_(std::move(initial_leak_area_m2)) {
  if (names_.size() != leak_area_m2_.size()) {
    throw std::invalid_argument("LeakageMerger: " + std::to_string(names_.size()) + " names but " +
                                std::to_string(leak_area_m2_.size()) + " areas");
  }
  for (std::size_t i = 0; i < names_.size(); ++i) index_.emplace(names_[i], i);
}

std::size_t LeakageMerger::indexOf(std::string_view name) const {
  const auto found = index_.find(name);
  return found == index_.end() ? names_.size() : found->second;
}

std::string LeakageMerger::check(const climbsim::Leakage& part) const {
  std::vector<std::size_t> indices;
  std::vector<char> seen;
  return checkIndexed(part, indices, seen);
}

std::string LeakageMerger::checkIndexed(const climbsim::Leakage& part, std::vector<std::size_t>& indices,
                                        std::vector<char>& seen) const {
  indices.clear();
  seen.assign(names_.size(), 0);
  for (const auto& s : part.segments()) {
    const char* name = s.segment().c_str();
    const std::size_t i = indexOf(name);
    if (i == names_.size()) return std::string("segment '") + name + "' is not a segment of the robot";
    if (seen[i] != 0) return std::string("segment '") + name + "' given twice";
    seen[i] = 1;
    if (!std::isfinite(s.leak_area_m2()) || s.leak_area_m2() < 0.0) {
      return std::string("segment '") + name + "': leak_area_m2 = " + fmt(s.leak_area_m2()) + " (must be finite and >= 0)";
    }
    if (!std::isfinite(s.mean_gap_m())) {
      return std::string("segment '") + name + "': mean_gap_m = " + fmt(s.mean_gap_m()) + " (must be finite)";
    }
    indices.push_back(i);
  }
  return {};
}

const std::vector<double>& LeakageMerger::merge(const std::vector<climbsim::Leakage>& parts) {
  covered_.assign(names_.size(), 0);
  for (const auto& part : parts) {
    std::string reason = checkIndexed(part, indices_, seen_);
    if (reason.empty()) {
      for (std::size_t k = 0; k < indices_.size(); ++k) {
        if (covered_[indices_[k]] != 0) {
          reason = std::string("segment '") + part.segments()[k].segment().c_str() +
                   "' also given by another part of this step";
          break;
        }
      }
    }
    if (!reason.empty()) {
      ++dropped_;
      spdlog::warn("sealing/Leakage from '{}' at step {}: {}; dropped ({} so far), last valid areas held",
                   part.source().c_str(), part.step(), reason, dropped_);
      continue;
    }
    for (std::size_t k = 0; k < indices_.size(); ++k) {
      covered_[indices_[k]] = 1;
      leak_area_m2_[indices_[k]] = part.segments()[k].leak_area_m2();
    }
  }
  return leak_area_m2_;
}

}  // namespace climbsim
