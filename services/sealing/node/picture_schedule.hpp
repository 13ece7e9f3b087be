#pragma once
/// @file
/// When the sealing service publishes the pictures a run keeps (no DDS): for each requested
/// time t of the scenario's pictures.sealing_at_s, the first due step whose time is >= t
/// (round(t * 1e9) ns) and that has pictures (a valid depth image was computed). Several
/// requested times may fall on one step: it publishes once.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace climbsim::sealing {

class PictureSchedule {
 public:
  /// `at_s`: requested times [s], any order.
  explicit PictureSchedule(const std::vector<double>& at_s);

  /// True if a requested time <= t_ns is still unserved.
  bool due(std::int64_t t_ns) const { return next_ < at_ns_.size() && at_ns_[next_] <= t_ns; }
  /// Marks every requested time <= t_ns served (call after publishing at t_ns).
  void served(std::int64_t t_ns);
  bool empty() const { return at_ns_.empty(); }
  /// Requested times not served yet.
  std::size_t pending() const { return at_ns_.size() - next_; }

 private:
  std::vector<std::int64_t> at_ns_;  ///< sorted
  std::size_t next_ = 0;
};

}  // namespace climbsim::sealing
