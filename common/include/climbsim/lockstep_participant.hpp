#pragma once
/// @file
/// The participant side of the lockstep clock (DESIGN.md §2), used by every service:
/// ready announcement, run start, matching of data endpoints, grant handling with
/// period and offset, stamped inputs and outputs, done, stop.

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/dds_context.hpp"
#include "climbsim/schedule.hpp"
#include "clockPubSubTypes.h"

namespace CLI {
class App;
}

namespace climbsim {

/// One step the clock granted to this participant: t_ns = step * dt_ns.
struct StepContext {
  std::uint64_t step = 0;
  std::int64_t t_ns = 0;   ///< simulation time at the start of the step [ns]
  std::int64_t dt_ns = 0;  ///< length of one clock step [ns]
};

/// Configuration of a lockstep participant.
struct ParticipantOptions {
  std::string name;
  Schedule schedule;
  DdsSettings dds;
  /// How long to wait for the clock and the run start before giving up [s].
  double start_timeout_s = 60.0;

  /// Adds --name, --period, --offset, --start-timeout-s, --domain, --qos.
  void addOptions(CLI::App& app);
  /// Validates and resolves (environment, defaults); throws ConfigError.
  void resolve();
};

class LockstepParticipant;

namespace detail {
/// Type-erased view of a stamped input, for the participant's matching and draining.
class InputPort {
 public:
  virtual ~InputPort() = default;
  virtual const std::string& topic() const = 0;
  virtual int matchedWriters() const = 0;
  virtual void drain() = 0;
};
/// Type-erased view of a stamped output.
class OutputPort {
 public:
  virtual ~OutputPort() = default;
  virtual const std::string& topic() const = 0;
  virtual int matchedReaders() const = 0;
};
}  // namespace detail

/// A topic read inside the lockstep. Samples must have `source`, `step` and `t_ns` fields
/// (set by StampedOutput::write).
template <class PubSubT>
class StampedInput : public detail::InputPort {
 public:
  using Sample = typename PubSubT::type;

  StampedInput(LockstepParticipant& owner, const std::string& topic);

  /// The sample each producer of the topic wrote at its last due step before ctx.step
  /// (zero-order hold), waiting for each one to arrive; ordered by producer name.
  /// Producers that have not been due yet contribute nothing. Throws if the run stops.
  std::vector<Sample> get(const StepContext& ctx);

  const std::string& topic() const override { return topic_; }
  int matchedWriters() const override { return reader_.matchedWriters(); }
  void drain() override;

 private:
  LockstepParticipant& owner_;
  std::string topic_;
  Reader<PubSubT> reader_;
  std::map<std::string, std::deque<Sample>> by_source_;
};

/// A topic written inside the lockstep, stamped with the step being computed.
template <class PubSubT>
class StampedOutput : public detail::OutputPort {
 public:
  using Sample = typename PubSubT::type;

  StampedOutput(LockstepParticipant& owner, const std::string& topic);

  /// Sets sample.source, .step and .t_ns from ctx and writes it.
  void write(const StepContext& ctx, Sample& sample);

  const std::string& topic() const override { return writer_.topicName(); }
  int matchedReaders() const override { return writer_.matchedReaders(); }

 private:
  LockstepParticipant& owner_;
  Writer<PubSubT> writer_;
};

/// Thrown from waits inside a step when the run ends; run() turns it into an exit code.
struct RunEnded {
  int exit_code;
};

/// A process on the clock's roster. Declare inputs and outputs, then run().
class LockstepParticipant {
 public:
  using StepFn = std::function<void(const StepContext&)>;

  /// Creates the DDS participant and the clock endpoints. Throws ConfigError.
  explicit LockstepParticipant(const ParticipantOptions& options);
  ~LockstepParticipant();

  /// Declares a stamped input (before run()). The participant waits for it every step.
  template <class PubSubT>
  StampedInput<PubSubT>& input(const std::string& topic) {
    auto port = std::make_unique<StampedInput<PubSubT>>(*this, topic);
    auto& ref = *port;
    inputs_.push_back(std::move(port));
    return ref;
  }

  /// Declares a stamped output (before run()).
  template <class PubSubT>
  StampedOutput<PubSubT>& output(const std::string& topic) {
    auto port = std::make_unique<StampedOutput<PubSubT>>(*this, topic);
    auto& ref = *port;
    outputs_.push_back(std::move(port));
    return ref;
  }

  /// Announces ready, waits for the run start, calls `step` for every granted step at
  /// which this participant is due, until the clock stops the run. Returns the process
  /// exit code (ExitCode); a `step` that throws fails the run with its message.
  int run(const StepFn& step);

  const std::string& name() const { return options_.name; }
  const Schedule& schedule() const { return options_.schedule; }
  DdsContext& dds() { return *dds_; }
  Notifier& notifier() { return notifier_; }

  // --- used by StampedInput / StampedOutput ---
  /// Producers (name, schedule) of a topic on this run's roster, sorted by name.
  std::vector<std::pair<std::string, Schedule>> producersOf(const std::string& topic) const;
  /// Waits for news from DDS (or `timeout`), watching the control plane; throws RunEnded.
  void waitForNews(std::uint64_t seen_generation);
  /// The step currently being computed, if any.
  std::optional<std::uint64_t> currentStep() const { return current_step_; }

 private:
  void pollControl();
  void waitUntil(const std::function<bool()>& condition, std::chrono::steady_clock::time_point deadline,
                 const std::string& what);
  void announceReady();
  void awaitRunStart(std::chrono::steady_clock::time_point deadline);
  void armDataEndpoints(std::chrono::steady_clock::time_point deadline);
  void sendDone(std::uint64_t step, climbsim::StepDoneKind kind, const std::string& message);
  int exitCodeForStop(const climbsim::Stop& stop) const;
  void failRun(const std::string& message);

  ParticipantOptions options_;
  Notifier notifier_;
  std::unique_ptr<DdsContext> dds_;
  std::unique_ptr<Reader<climbsim::StepGrantPubSubType>> grant_reader_;
  std::unique_ptr<Reader<climbsim::RunStartPubSubType>> run_start_reader_;
  std::unique_ptr<Reader<climbsim::StopPubSubType>> stop_reader_;
  std::unique_ptr<Writer<climbsim::StepDonePubSubType>> done_writer_;
  std::unique_ptr<Writer<climbsim::ParticipantReadyPubSubType>> ready_writer_;
  std::vector<std::unique_ptr<detail::InputPort>> inputs_;
  std::vector<std::unique_ptr<detail::OutputPort>> outputs_;

  std::optional<climbsim::RunStart> run_start_;
  std::optional<climbsim::Stop> stop_;
  bool clock_seen_ = false;
  bool clock_lost_ = false;
  std::deque<climbsim::StepGrant> grants_;
  std::optional<std::uint64_t> current_step_;
  std::optional<std::uint64_t> last_step_;
};

// ---------------------------------------------------------------- templates

template <class PubSubT>
StampedInput<PubSubT>::StampedInput(LockstepParticipant& owner, const std::string& topic)
    : owner_(owner), topic_(topic), reader_(owner.dds(), topic, qos::kStepData, owner.notifier()) {}

template <class PubSubT>
void StampedInput<PubSubT>::drain() {
  for (auto& received : reader_.take()) {
    auto& queue = by_source_[received.data.source().c_str()];
    queue.push_back(std::move(received.data));
    // A consumer needs at most the producer's latest stamp and the one after it.
    while (queue.size() > 8) {
      queue.pop_front();
    }
  }
}

template <class PubSubT>
std::vector<typename PubSubT::type> StampedInput<PubSubT>::get(const StepContext& ctx) {
  std::vector<Sample> out;
  for (const auto& [producer, schedule] : owner_.producersOf(topic_)) {
    const auto stamp = schedule.lastDueBefore(ctx.step);
    if (!stamp) {
      continue;
    }
    while (true) {
      const auto seen = owner_.notifier().generation();
      drain();
      auto& queue = by_source_[producer];
      while (!queue.empty() && queue.front().step() < *stamp) {
        queue.pop_front();
      }
      if (!queue.empty() && queue.front().step() == *stamp) {
        out.push_back(queue.front());
        break;
      }
      if (!queue.empty()) {
        throw std::runtime_error("topic '" + topic_ + "': needed the sample of '" + producer + "' stamped " +
                                 std::to_string(*stamp) + " but the next one is stamped " +
                                 std::to_string(queue.front().step()));
      }
      owner_.waitForNews(seen);
    }
  }
  return out;
}

template <class PubSubT>
StampedOutput<PubSubT>::StampedOutput(LockstepParticipant& owner, const std::string& topic)
    : owner_(owner), writer_(owner.dds(), topic, qos::kStepData, owner.notifier()) {}

template <class PubSubT>
void StampedOutput<PubSubT>::write(const StepContext& ctx, Sample& sample) {
  if (owner_.currentStep() != ctx.step) {
    throw std::logic_error("topic '" + topic() + "': written outside its step " + std::to_string(ctx.step));
  }
  sample.source(owner_.name());
  sample.step(ctx.step);
  sample.t_ns(ctx.t_ns);
  writer_.write(sample);
}

}  // namespace climbsim
