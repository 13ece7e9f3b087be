#include "climbsim/observer_feed.hpp"

#include <algorithm>
#include <vector>

namespace climbsim {

void ObserverFeed::add(const RecordBatch& batch) {
  for (const auto& sample : batch.samples()) {
    const std::string topic = sample.topic().to_string();
    auto it = latest_.find(topic);
    if (it == latest_.end()) {
      latest_.emplace(topic, sample);
    } else if (sample.step() >= it->second.step()) {
      it->second = sample;
    }
  }
}

RecordBatch ObserverFeed::take(Clock::time_point now, const std::string& source, std::uint64_t run_id,
                               std::uint64_t end_step) {
  RecordBatch out;
  out.source(source);
  out.run_id(run_id);
  out.end_step(end_step);
  std::vector<RecordedSample*> order;
  order.reserve(latest_.size());
  for (auto& entry : latest_) order.push_back(&entry.second);
  std::stable_sort(order.begin(), order.end(),
                   [](const RecordedSample* a, const RecordedSample* b) { return a->step() < b->step(); });
  out.first_step(order.empty() ? end_step : order.front()->step());
  for (auto* sample : order) out.samples().push_back(std::move(*sample));
  latest_.clear();
  last_send_ = now;
  return out;
}

}  // namespace climbsim
