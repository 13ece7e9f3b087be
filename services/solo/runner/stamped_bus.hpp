#pragma once
/// @file
/// The in-process stand-in for the stamped step-data topics of the lockstep
/// (docs/design.md#horizons), for `climbsim solo`: no DDS, one thread. A consumer at step k reads,
/// of every producer of a topic (ordered by producer name, as LockstepParticipant::producersOf
/// gives them), the sample that producer wrote at its last due step before k (zero-order hold; at
/// or before k for a same-step input), exactly the stamp StampedInput::get waits for.

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "climbsim/schedule.hpp"

namespace climbsim::solo {

/// Which stamp of a producer a consumer reads at step k (as climbsim::InputLag).
enum class Lag {
  kOneStep,   ///< the producer's last due step < k (every input of the default composition)
  kSameStep,  ///< the producer's last due step <= k (the producer must have run at k first)
};

/// One topic: its producers' schedules and the samples they wrote, by stamp.
template <class Sample>
class StampedTopic {
 public:
  explicit StampedTopic(std::string name) : name_(std::move(name)) {}

  /// Declares a producer of the topic with its schedule (before the first step).
  void addProducer(const std::string& producer, const Schedule& schedule) { producers_[producer].schedule = schedule; }

  /// Stamps the sample as StampedOutput::write does (source = producer, step, t_ns) and keeps
  /// it. std::logic_error for an unknown producer, a step at which it is not due, or a step
  /// not after its previous one.
  void write(const std::string& producer, std::uint64_t step, std::int64_t t_ns, Sample sample) {
    auto it = producers_.find(producer);
    if (it == producers_.end()) throw std::logic_error("topic '" + name_ + "': '" + producer + "' is no producer");
    auto& p = it->second;
    if (!p.schedule.isDue(step)) {
      throw std::logic_error("topic '" + name_ + "': '" + producer + "' wrote at step " + std::to_string(step) +
                             " where it is not due");
    }
    if (!p.samples.empty() && p.samples.rbegin()->first >= step) {
      throw std::logic_error("topic '" + name_ + "': '" + producer + "' wrote step " + std::to_string(step) + " twice");
    }
    sample.source(producer);
    sample.step(step);
    sample.t_ns(t_ns);
    p.samples.emplace(step, std::move(sample));
    // A consumer reads the newest or (one-step lag, after the producer ran) the one before.
    while (p.samples.size() > 2) p.samples.erase(p.samples.begin());
  }

  /// The samples a consumer reads at `step` (one per producer that has been due, by producer
  /// name). std::logic_error if a needed stamp is missing (a producer that has not run yet:
  /// an ordering bug of the caller).
  std::vector<Sample> get(std::uint64_t step, Lag lag) const {
    std::vector<Sample> out;
    for (const auto& [producer, p] : producers_) {
      if (!p.schedule.lastDueBefore(lag == Lag::kSameStep ? step + 1 : step)) continue;
      out.push_back(getOne(producer, p, step, lag));
    }
    return out;
  }

  /// A producer's initial state (StampedOutput::recordInitial): stamped as written at step 0
  /// and given to the recorder for the steps before the producer's first due step.
  void setInitial(const std::string& producer, Sample sample) {
    auto it = producers_.find(producer);
    if (it == producers_.end()) throw std::logic_error("topic '" + name_ + "': '" + producer + "' is no producer");
    sample.source(producer);
    sample.step(0);
    sample.t_ns(0);
    it->second.initial = std::move(sample);
  }

  /// What the recorder reads at `step` (RecordedInput::get): get(step, Lag::kOneStep), where a
  /// producer that has not been due yet gives its initial state if it set one.
  std::vector<Sample> getRecorded(std::uint64_t step) const {
    std::vector<Sample> out;
    for (const auto& [producer, p] : producers_) {
      if (p.schedule.lastDueBefore(step)) {
        const auto stamped = getOne(producer, p, step, Lag::kOneStep);
        out.push_back(stamped);
      } else if (p.initial) {
        out.push_back(*p.initial);
      }
    }
    return out;
  }

  const std::string& name() const { return name_; }

 private:
  struct Producer {
    Schedule schedule;
    std::map<std::uint64_t, Sample> samples;  ///< by stamp, the last two
    std::optional<Sample> initial;            ///< setInitial's
  };

  /// The sample of `producer` (which has been due before `step`) that `lag` gives at `step`.
  const Sample& getOne(const std::string& producer, const Producer& p, std::uint64_t step, Lag lag) const {
    const auto stamp = p.schedule.lastDueBefore(lag == Lag::kSameStep ? step + 1 : step);
    const auto it = p.samples.find(*stamp);
    if (it == p.samples.end()) {
      throw std::logic_error("topic '" + name_ + "': the sample of '" + producer + "' stamped " +
                             std::to_string(*stamp) + " (read at step " + std::to_string(step) + ") is not there");
    }
    return it->second;
  }
  std::string name_;
  std::map<std::string, Producer> producers_;  ///< ordered by name
};

}  // namespace climbsim::solo
