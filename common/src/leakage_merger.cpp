#include "climbsim/leakage_merger.hpp"

#include <cmath>
#include <set>
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

std::string LeakageMerger::check(const climbsim::Leakage& part) const {
  std::set<std::string> seen;
  for (const auto& s : part.segments()) {
    const std::string name = s.segment().c_str();
    if (index_.count(name) == 0) return "segment '" + name + "' is not a segment of the robot";
    if (!seen.insert(name).second) return "segment '" + name + "' given twice";
    if (!std::isfinite(s.leak_area_m2()) || s.leak_area_m2() < 0.0) {
      return "segment '" + name + "': leak_area_m2 = " + fmt(s.leak_area_m2()) + " (must be finite and >= 0)";
    }
    if (!std::isfinite(s.mean_gap_m())) {
      return "segment '" + name + "': mean_gap_m = " + fmt(s.mean_gap_m()) + " (must be finite)";
    }
  }
  return {};
}

const std::vector<double>& LeakageMerger::merge(const std::vector<climbsim::Leakage>& parts) {
  std::set<std::string> covered;
  for (const auto& part : parts) {
    std::string reason = check(part);
    if (reason.empty()) {
      for (const auto& s : part.segments()) {
        if (covered.count(s.segment().c_str()) != 0) {
          reason = std::string("segment '") + s.segment().c_str() + "' also given by another part of this step";
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
    for (const auto& s : part.segments()) {
      covered.insert(s.segment().c_str());
      leak_area_m2_[index_.at(s.segment().c_str())] = s.leak_area_m2();
    }
  }
  return leak_area_m2_;
}

}  // namespace climbsim
