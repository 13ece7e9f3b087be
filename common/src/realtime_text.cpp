#include "climbsim/realtime_text.hpp"

#include <cmath>
#include <cstdio>

namespace climbsim {

std::string realtimeText(double factor) {
  if (!(std::isfinite(factor) && factor > 0.0)) return "n/a real time";
  char text[48];
  if (factor >= 10.0) {
    std::snprintf(text, sizeof text, "%.0fx real time", factor);
  } else if (factor >= 1.0) {
    std::snprintf(text, sizeof text, "%.1fx real time", factor);
  } else {
    std::snprintf(text, sizeof text, "%.2gx real time", factor);
  }
  return text;
}

std::string realtimeText(double sim_s, double wall_s) {
  if (!(std::isfinite(wall_s) && wall_s >= kMinMeasuredWall_s)) {
    char text[64];
    std::snprintf(text, sizeof text, "n/a real time (%.2g ms wall)", std::isfinite(wall_s) ? wall_s * 1e3 : 0.0);
    return text;
  }
  if (!(std::isfinite(sim_s) && sim_s > 0.0)) return "n/a real time (nothing simulated)";
  return realtimeText(sim_s / wall_s);
}

}  // namespace climbsim
