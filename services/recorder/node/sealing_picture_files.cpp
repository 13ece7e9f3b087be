#include "sealing_picture_files.hpp"

#include <algorithm>
#include <cmath>

#include "plot/picture_names.hpp"

namespace climbsim::recorder {

std::int64_t secondsToNs(double t_s) { return static_cast<std::int64_t>(std::llround(t_s * 1e9)); }

SealingPictureFiles::SealingPictureFiles(std::vector<double> at_s, std::vector<std::string> kinds)
    : at_s_(std::move(at_s)), kinds_(std::move(kinds)) {
  std::sort(at_s_.begin(), at_s_.end());
  at_s_.erase(std::unique(at_s_.begin(), at_s_.end(),
                          [](double a, double b) { return secondsToNs(a) == secondsToNs(b); }),
              at_s_.end());
}

std::vector<std::string> SealingPictureFiles::filesFor(const std::string& kind, std::int64_t t_ns) {
  std::vector<std::string> out;
  if (std::find(kinds_.begin(), kinds_.end(), kind) == kinds_.end()) return out;
  for (std::size_t i = 0; i < at_s_.size() && secondsToNs(at_s_[i]) <= t_ns; ++i) {
    if (done_.insert({i, kind}).second) out.push_back(plot::sealingPictureName(kind, at_s_[i]));
  }
  return out;
}

std::size_t SealingPictureFiles::missingUpTo(std::int64_t up_to_ns) const {
  std::size_t missing = 0;
  for (std::size_t i = 0; i < at_s_.size() && secondsToNs(at_s_[i]) <= up_to_ns; ++i) {
    for (const auto& k : kinds_) missing += done_.count({i, k}) == 0 ? 1 : 0;
  }
  return missing;
}

}  // namespace climbsim::recorder
