#include "fall_report.hpp"

#include <cmath>
#include <cstdio>

namespace climbsim::drive {

std::string fellReason(const DriveOutputs& outputs, std::int64_t t_ns) {
  const auto& p = outputs.position_m;
  const auto& v = outputs.linear_velocity_mps;
  char reason[200];
  std::snprintf(reason, sizeof(reason),
                "FELL at t = %.3f s: the robot left the wall at x = %.3f m, y = %.3f m (%.3f m off the wall "
                "plane, sliding at %.2f m/s)",
                static_cast<double>(t_ns) * 1e-9, p[0], p[1], p[2], std::hypot(v[0], v[1]));
  return reason;
}

}  // namespace climbsim::drive
