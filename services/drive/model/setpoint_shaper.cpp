#include "setpoint_shaper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace climbsim::drive {

SetpointShaper::SetpointShaper(std::size_t wheels, int delay_substeps, double max_rate_radps)
    : delay_(static_cast<std::size_t>(std::max(0, delay_substeps))),
      max_rate_radps_(max_rate_radps),
      pipeline_(delay_, std::vector<WheelSetpoint>(wheels)),
      refs_(wheels) {
  if (!(max_rate_radps > 0.0)) throw std::invalid_argument("SetpointShaper: rate limit must be > 0");
}

void SetpointShaper::advance(const std::vector<WheelSetpoint>& targets, double h_s) {
  if (targets.size() != refs_.size()) throw std::invalid_argument("SetpointShaper: wrong number of targets");
  pipeline_.push_back(targets);
  const std::vector<WheelSetpoint> due = std::move(pipeline_.front());
  pipeline_.pop_front();
  const double max_step = max_rate_radps_ * h_s;
  double worst_error_rad = 0.0;
  for (std::size_t i = 0; i < refs_.size(); ++i) {
    auto& r = refs_[i];
    const double step = std::clamp(due[i].steering_rad - r.steering_rad, -max_step, max_step);
    r.steering_rad += step;
    r.steering_rate_radps = step / h_s;
    worst_error_rad = std::max(worst_error_rad, std::fabs(due[i].steering_rad - r.steering_rad));
  }
  const double together = std::max(0.0, 1.0 - worst_error_rad / kAlignmentWindowRad);
  for (std::size_t i = 0; i < refs_.size(); ++i) refs_[i].wheel_speed_radps = due[i].wheel_speed_radps * together;
}

}  // namespace climbsim::drive
