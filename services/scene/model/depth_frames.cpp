#include "depth_frames.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::scene {

WholeDepthFrames::WholeDepthFrames(const DepthFrameChoice& choice)
    : masked_(choice.masked()),
      every_frame_(choice.every_frame_whole),
      depth_grids_(choice.depth_grids),
      read_lag_ns_(choice.read_lag_ns) {
  // As the sealing's PictureSchedule: round(t * 1e9) ns.
  for (const double t_s : choice.read_at_s) read_at_ns_.push_back(static_cast<std::int64_t>(std::llround(t_s * 1e9)));
  std::sort(read_at_ns_.begin(), read_at_ns_.end());
}

bool WholeDepthFrames::whole(std::int64_t t_ns) {
  bool whole = !masked_ || every_frame_;
  if (depth_grids_ && t_ns >= next_grid_ns_) {  // DepthGridSchedule::offer's rule
    next_grid_ns_ = (t_ns / kWholeInterval_ns + 1) * kWholeInterval_ns;
    whole = true;
  }
  const std::int64_t read_ns = t_ns + read_lag_ns_;  // the sealing's step that reads this frame
  while (next_read_ < read_at_ns_.size() && read_at_ns_[next_read_] <= read_ns) {
    ++next_read_;
    whole = true;
  }
  return whole;
}

}  // namespace climbsim::scene
