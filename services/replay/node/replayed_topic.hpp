#pragma once
/// @file
/// A recorded topic played back on the lockstep (docs/recordings.md#replay): the samples one
/// producer wrote, decoded from the recording and written again at their own steps by a
/// participant of the producer's name and schedule, so that they travel as the recorded bytes.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "climbsim/errors.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/recording/recorded_messages.hpp"

namespace climbsim::replay {

/// What the player steps, whatever the topic's type.
class ReplayedPort {
 public:
  virtual ~ReplayedPort() = default;
  /// Writes the recorded sample of ctx.step, if the recording has one (a stamp that no row of
  /// the recording read, such as the last step's, has none: nobody reads it).
  virtual void write(const StepContext& ctx) = 0;
  /// Samples played so far.
  virtual std::uint64_t played() const = 0;
};

template <class PubSubT>
class ReplayedTopic : public ReplayedPort {
 public:
  using Sample = typename PubSubT::type;

  /// The samples of `messages` whose source is `participant`'s name, written by an output of
  /// `topic` that this declares on `participant` (before its run) unless there are none: a
  /// participant declares only the topics its producer wrote. The producer's initial state is its
  /// first message stamped step 0 when two are (the second is step 0's output); a single one
  /// stamped step 0 is both (a recording does not write a sample equal to its producer's one
  /// before). Throws ConfigError if a message does not decode.
  ReplayedTopic(LockstepParticipant& participant, const std::string& topic,
                const std::vector<recording::RecordedMessage>& messages) {
    PubSubT type;
    std::vector<Sample> samples;
    for (const auto& m : messages) {
      eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(m.cdr.size()));
      std::copy(m.cdr.begin(), m.cdr.end(), payload.data);
      payload.length = static_cast<std::uint32_t>(m.cdr.size());
      Sample sample;
      if (!type.deserialize(&payload, &sample)) throw ConfigError("recording: a sample of '" + topic + "' does not decode");
      if (sample.source() == participant.name()) samples.push_back(std::move(sample));
    }
    if (samples.empty()) return;
    std::size_t first = 0;
    if (samples[0].step() == 0) {
      initial_ = samples[0];
      if (samples.size() > 1 && samples[1].step() == 0) first = 1;
    }
    for (std::size_t i = first; i < samples.size(); ++i) by_step_[samples[i].step()] = samples[i];
    output_ = &participant.output<PubSubT>(topic);
    if (initial_) output_->recordInitial(*initial_);
  }

  /// False if the recording has no sample of this producer on the topic (nothing declared).
  bool plays() const { return output_ != nullptr; }

  void write(const StepContext& ctx) override {
    const auto found = by_step_.find(ctx.step);
    if (output_ == nullptr || found == by_step_.end()) return;
    output_->write(ctx, found->second);
    ++played_;
  }
  std::uint64_t played() const override { return played_; }

 private:
  StampedOutput<PubSubT>* output_ = nullptr;
  std::optional<Sample> initial_;
  std::map<std::uint64_t, Sample> by_step_;
  std::uint64_t played_ = 0;
};

}  // namespace climbsim::replay
