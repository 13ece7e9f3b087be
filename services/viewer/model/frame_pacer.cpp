#include "frame_pacer.hpp"

#include <stdexcept>

namespace climbsim::viewer {

FramePacer::FramePacer(double max_fps) {
  if (!(max_fps > 0.0)) throw std::invalid_argument("frame rate must be > 0");
  period_ns_ = static_cast<std::int64_t>(1e9 / max_fps);
}

bool FramePacer::take(std::int64_t now_ns) {
  if (now_ns < next_ns_) return false;
  // From now, not from the missed slot: a late frame does not buy a burst of catch-up frames.
  next_ns_ = now_ns + period_ns_;
  return true;
}

}  // namespace climbsim::viewer
