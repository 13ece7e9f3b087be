#pragma once
/// @file
/// At most `max_fps` frames per second: the viewer sends the latest state when a frame is due
/// and something changed, never a backlog. Pure: the caller passes its monotonic time.

#include <cstdint>

namespace climbsim::viewer {

class FramePacer {
 public:
  /// `max_fps` > 0 frames per second.
  explicit FramePacer(double max_fps);

  /// True if a frame may be sent at `now_ns` (monotonic [ns]); then counts it as sent.
  bool take(std::int64_t now_ns);

  /// When the next frame may be sent [ns] (monotonic; anything <= now means "now").
  std::int64_t nextNs() const { return next_ns_; }

 private:
  std::int64_t period_ns_;
  std::int64_t next_ns_ = 0;
};

}  // namespace climbsim::viewer
