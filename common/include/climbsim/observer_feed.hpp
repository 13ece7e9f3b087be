#pragma once
/// @file
/// What a roster participant sends the run's observers (the viewer): a copy of its record
/// batches thinned out in wall time (topic record/ObserverBatch, best effort). A record batch
/// goes to the recorders with every acknowledgement (about 140 a second per producer at 5x real
/// time); an observer draws at most 30 frames a second, so each batch delivered to it beyond that
/// costs the producer a copy and a wake-up of the observer for nothing. The feed keeps the latest
/// sample of each recorded topic since its last send and sends them together at most once per
/// `period`; nothing it does reaches the trace (observers never gate a step).

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

#include "record.h"

namespace climbsim {

/// The latest recorded sample of each topic, sent at most once per period. Not thread-safe
/// (the participant's step thread owns it).
class ObserverFeed {
 public:
  using Clock = std::chrono::steady_clock;

  /// `period`: least wall time between two sends (1/30 s: the viewer's frame rate).
  explicit ObserverFeed(std::chrono::nanoseconds period) : period_(period) {}

  /// Keeps each topic's last sample of `batch` (the highest step; of equal steps the later one).
  void add(const RecordBatch& batch);

  /// True if a sample waits and `period` has passed since the last send at `now`.
  bool due(Clock::time_point now) const { return !latest_.empty() && now - last_send_ >= period_; }

  /// True if a sample waits (sent at once when the run ends, whatever the period).
  bool pending() const { return !latest_.empty(); }

  /// The waiting samples as one batch (in step order, then topic), stamped with `source`,
  /// `run_id` and end_step `end_step`; empties the feed and counts `now` as its last send.
  RecordBatch take(Clock::time_point now, const std::string& source, std::uint64_t run_id, std::uint64_t end_step);

 private:
  std::chrono::nanoseconds period_;
  Clock::time_point last_send_{};
  std::map<std::string, RecordedSample> latest_;  ///< topic -> its newest sample
};

}  // namespace climbsim
