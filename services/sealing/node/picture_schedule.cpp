#include "picture_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::sealing {

PictureSchedule::PictureSchedule(const std::vector<double>& at_s) {
  for (double t : at_s) at_ns_.push_back(static_cast<std::int64_t>(std::llround(t * 1e9)));
  std::sort(at_ns_.begin(), at_ns_.end());
}

void PictureSchedule::served(std::int64_t t_ns) {
  while (next_ < at_ns_.size() && at_ns_[next_] <= t_ns) ++next_;
}

}  // namespace climbsim::sealing
