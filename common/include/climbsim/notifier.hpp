#pragma once
/// @file
/// Wakes one waiting thread when any DDS listener has news, without losing a wake-up.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace climbsim {

/// A generation counter with a condition variable. Read generation(), look at every
/// source, then waitChanged(seen, deadline): a notify() between the look and the wait
/// is not lost.
class Notifier {
 public:
  using Clock = std::chrono::steady_clock;

  std::uint64_t generation() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return generation_;
  }

  void notify() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++generation_;
    }
    cv_.notify_all();
  }

  /// Returns true if notify() was called since `seen`, false at `deadline`.
  bool waitChanged(std::uint64_t seen, Clock::time_point deadline) const {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_until(lock, deadline, [&] { return generation_ != seen; });
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable cv_;
  std::uint64_t generation_ = 0;
};

}  // namespace climbsim
