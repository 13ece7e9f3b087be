#pragma once
/// @file
/// The participant side of the simulation clock (docs/design.md#the-shared-simulation-clock), used
/// by every service: ready announcement, run start, matching of data endpoints, the horizon
/// protocol with period and offset, stamped inputs and outputs, recording batches, progress, stop.
///
/// A participant computes its due step k as soon as k < H (the clock's horizon) and every
/// stamped input it reads for k has arrived; it acknowledges its progress in batches
/// (every W/2 steps, at the horizon, and before a long wait). Outputs are written only at
/// the stamps some consumer on the roster reads; samples of topics a recorder reads are
/// also collected and sent to it as one RecordBatch per acknowledgement.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "climbsim/dds_context.hpp"
#include "climbsim/schedule.hpp"
#include "clockPubSubTypes.h"
#include "climbsim/observer_feed.hpp"
#include "recordPubSubTypes.h"

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

/// Which stamp of a producer an input reads at step k.
enum class InputLag {
  kOneStep,   ///< the producer's last due step < k (the default: no same-step data)
  kSameStep,  ///< the producer's last due step <= k; the clock refuses cycles of these
};

namespace detail {
/// Type-erased view of a stamped input, for the participant's matching and draining.
class InputPort {
 public:
  virtual ~InputPort() = default;
  virtual const std::string& topic() const = 0;
  virtual int matchedWriters() const = 0;
  /// The DDS participants of the writers matched now, if known (Reader::matchedParticipants).
  virtual std::optional<std::vector<ParticipantId>> matchedParticipants() const = 0;
  virtual void drain() = 0;
  virtual InputLag lag() const = 0;
  /// The producers this input reads (empty: every producer of the topic on the roster).
  virtual const std::vector<std::string>& from() const = 0;
};
/// Type-erased view of a recorded input: samples arrive inside RecordBatch samples.
class RecordedPort {
 public:
  virtual ~RecordedPort() = default;
  virtual const std::string& topic() const = 0;
  /// Takes one recorded sample (its CDR bytes) of `source`; throws if it does not decode.
  virtual void accept(const std::string& source, const std::vector<std::uint8_t>& cdr) = 0;
  /// Takes `source`'s initial state of the topic (from its initial batch); throws if it does not decode.
  virtual void acceptInitial(const std::string& source, const std::vector<std::uint8_t>& cdr) = 0;
};

/// Received samples by producer, and the zero-order-hold lookup of docs/design.md#horizons.
template <class Sample>
class StampQueues {
 public:
  void push(const std::string& source, Sample&& sample);
  /// The sample each producer of `topic` (each one named in `only`, if not empty) wrote at the
  /// stamp `lag` gives for ctx.step, calling `drain` and waiting through `owner` until each
  /// has arrived. A producer that has not been due yet contributes `before_first(producer)`
  /// (a std::optional<Sample>).
  template <class DrainFn, class BeforeFirstFn>
  std::vector<Sample> get(LockstepParticipant& owner, const std::string& topic, std::uint64_t step, InputLag lag,
                          DrainFn drain, BeforeFirstFn before_first, const std::vector<std::string>& only = {});
  /// Every queued sample, by producer name then in arrival order; the queues are left empty.
  std::vector<Sample> takeAll();

 private:
  std::map<std::string, std::deque<Sample>> by_source_;
};

/// A producer of a topic as the clock bound it at ready time: its roster name and the
/// DDS participant it is (sender_identity.hpp).
struct ProducerIdentity {
  std::string name;
  ParticipantId id;
};

/// True if a sample claiming `source` from DDS participant `sender` comes from one of
/// `producers`: 12-byte compares and a name compare, no allocation (every stamped sample).
inline bool sentByProducer(const std::vector<ProducerIdentity>& producers, const char* source,
                           const ParticipantId& sender) {
  for (const auto& p : producers) {
    if (p.id == sender && p.name == source) {
      return true;
    }
  }
  return false;
}
}  // namespace detail
namespace detail {
/// Type-erased view of a stamped output.
class OutputPort {
 public:
  virtual ~OutputPort() = default;
  virtual const std::string& topic() const = 0;
  virtual int matchedReaders() const = 0;
  /// The DDS participants of the readers matched now, if known (Writer::matchedParticipants).
  virtual std::optional<std::vector<ParticipantId>> matchedParticipants() const = 0;
};
}  // namespace detail

/// A topic read inside the lockstep. Samples must have `source`, `step` and `t_ns` fields
/// (set by StampedOutput::write).
template <class PubSubT>
class StampedInput : public detail::InputPort {
 public:
  using Sample = typename PubSubT::type;

  /// `from`: the producers to read (empty: all); the others' samples are never sent here
  /// (DDS partitions), and the run fails before step 0 if one is not a producer of the topic.
  StampedInput(LockstepParticipant& owner, const std::string& topic, InputLag lag,
               std::vector<std::string> from = {});

  /// The sample each producer of the topic (each one of `from`) wrote at its last due step before ctx.step
  /// (at or before it for InputLag::kSameStep; zero-order hold), waiting for each one to
  /// arrive; ordered by producer name. Producers that have not been due yet contribute
  /// nothing. Throws RunEnded if the run stops meanwhile.
  std::vector<Sample> get(const StepContext& ctx);

  const std::string& topic() const override { return topic_; }
  int matchedWriters() const override { return reader_.matchedWriters(); }
  std::optional<std::vector<ParticipantId>> matchedParticipants() const override {
    return reader_.matchedParticipants();
  }
  void drain() override;
  InputLag lag() const override { return lag_; }
  const std::vector<std::string>& from() const override { return from_; }

 private:
  LockstepParticipant& owner_;
  std::string topic_;
  InputLag lag_;
  std::vector<std::string> from_;
  Reader<PubSubT> reader_;
  detail::StampQueues<Sample> queues_;
  const std::vector<detail::ProducerIdentity>* producers_ = nullptr;  ///< set once the run started
};

/// A topic a recorder reads without a delivery per sample: its producers send the samples
/// in RecordBatch samples (record/RecordBatch), one per acknowledgement of progress. get()
/// answers exactly as StampedInput::get (same stamps, same samples, bit for bit).
template <class PubSubT>
class RecordedInput : public detail::RecordedPort {
 public:
  using Sample = typename PubSubT::type;

  RecordedInput(LockstepParticipant& owner, const std::string& topic) : owner_(owner), topic_(topic) {}

  /// As StampedInput::get with InputLag::kOneStep, except that a producer that has not been
  /// due yet (every producer at step 0) contributes its initial state, the sample it gave
  /// StampedOutput::recordInitial (waiting for its initial batch, which every producer of a
  /// recorded topic sends at the run start), or nothing if it gave none.
  std::vector<Sample> get(const StepContext& ctx);
  /// Every sample that came since the last call, without waiting: for topics not written at
  /// every due step (decimated ones such as scene/DepthGrid), which get() would wait for.
  /// Do not mix with get() on one input.
  std::vector<Sample> takeArrived();

  const std::string& topic() const override { return topic_; }
  void accept(const std::string& source, const std::vector<std::uint8_t>& cdr) override;
  void acceptInitial(const std::string& source, const std::vector<std::uint8_t>& cdr) override;

 private:
  Sample decode(const std::string& source, const std::vector<std::uint8_t>& cdr);

  LockstepParticipant& owner_;
  std::string topic_;
  PubSubT type_;
  detail::StampQueues<Sample> queues_;
  std::map<std::string, Sample> initial_;  ///< by producer
};

/// A topic written inside the lockstep, stamped with the step being computed.
template <class PubSubT>
class StampedOutput : public detail::OutputPort {
 public:
  using Sample = typename PubSubT::type;

  StampedOutput(LockstepParticipant& owner, const std::string& topic);

  /// Sets sample.source, .step and .t_ns from ctx; writes it if a consumer on the roster
  /// reads this stamp, and adds it to the record batch if a recorder reads the topic.
  void write(const StepContext& ctx, Sample& sample);

  /// Gives the topic's initial state: the producer's state before step 0, before any input
  /// (e.g. the pressures at ambient, the start pose). Call before run(), at most once; the
  /// sample is stamped step 0, t_ns 0 and sent to the recorders in the initial batch at the
  /// run start: the trace's row 0, and its rows before this producer's first due step.
  void recordInitial(Sample& sample);

  const std::string& topic() const override { return writer_.topicName(); }
  int matchedReaders() const override { return writer_.matchedReaders(); }
  std::optional<std::vector<ParticipantId>> matchedParticipants() const override {
    return writer_.matchedParticipants();
  }

 private:
  LockstepParticipant& owner_;
  Writer<PubSubT> writer_;
  PubSubT type_;
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

  /// Declares a stamped input (before run()). The participant waits for it every step, for
  /// the samples of every producer of the topic, or of those named in `from` only.
  template <class PubSubT>
  StampedInput<PubSubT>& input(const std::string& topic, InputLag lag = InputLag::kOneStep,
                               std::vector<std::string> from = {}) {
    auto port = std::make_unique<StampedInput<PubSubT>>(*this, topic, lag, std::move(from));
    auto& ref = *port;
    inputs_.push_back(std::move(port));
    return ref;
  }

  /// Declares a recorded input (before run()): the topic's samples come in record batches.
  template <class PubSubT>
  RecordedInput<PubSubT>& recordedInput(const std::string& topic) {
    auto port = std::make_unique<RecordedInput<PubSubT>>(*this, topic);
    auto& ref = *port;
    recorded_.push_back(std::move(port));
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

  /// Announces ready, waits for the run start, calls `step` for every due step below the
  /// clock's horizon, in order, until the clock stops the run. Returns the process exit
  /// code (ExitCode); a `step` that throws fails the run with its message.
  int run(const StepFn& step);

  const std::string& name() const { return options_.name; }
  /// Tells the clock (once) that the robot fell, from inside a step: the clock freezes the
  /// horizon like a stop, everyone finishes the steps below it (the trace keeps the fall),
  /// and the run ends with outcome "fell", exit code kExitFell, and `reason`.
  void reportFell(const std::string& reason);
  /// The clock's Stop of this run, once run() has returned because of it.
  const std::optional<climbsim::Stop>& stopMessage() const { return stop_; }
  /// The clock's RunStart of this run, once run() calls the first step (empty before).
  const std::optional<climbsim::RunStart>& runStartMessage() const { return run_start_; }
  const Schedule& schedule() const { return options_.schedule; }
  DdsContext& dds() { return *dds_; }
  Notifier& notifier() { return notifier_; }

  // --- used by StampedInput / StampedOutput ---
  /// Producers of `topic` and who they are, once the run started (nullptr before).
  const std::vector<detail::ProducerIdentity>* producerIdentities(const std::string& topic) const;
  /// Counts a sample whose sender is not who it must be, and logs it once per writer.
  void dropForeign(const std::string& topic, const std::string& writer, const std::string& why) {
    dropped_.drop(topic, writer, why);
  }
  /// Producers (name, schedule) of a topic on this run's roster, sorted by name.
  std::vector<std::pair<std::string, Schedule>> producersOf(const std::string& topic) const;
  /// Waits for news from DDS (or `timeout`), watching the control plane; throws RunEnded.
  /// Before a wait longer than kSlowWait it acknowledges its progress and sends its
  /// record batch, so that the clock's watchdog sees who really holds the run up.
  void waitForNews(std::uint64_t seen_generation);
  /// The step currently being computed, if any.
  std::optional<std::uint64_t> currentStep() const { return current_step_; }
  /// True if some consumer on the roster reads `topic`'s sample stamped `step` of this
  /// participant (directly, not through record batches).
  bool stampIsRead(const std::string& topic, std::uint64_t step) const;
  /// True if a recorder on the roster reads `topic` through record batches.
  bool isRecorded(const std::string& topic) const { return recorded_outputs_.count(topic) != 0; }
  /// Adds a sample's CDR bytes to the record batch (sent with the next acknowledgement).
  void record(const std::string& topic, std::uint64_t step, const eprosima::fastrtps::rtps::SerializedPayload_t& cdr);
  /// Keeps a topic's initial state (CDR bytes) for the initial batch (before run()).
  void recordInitial(const std::string& topic, const eprosima::fastrtps::rtps::SerializedPayload_t& cdr);
  /// Takes the record batches that arrived (recorders).
  void drainRecords();
  /// True once `producer`'s initial batch has arrived (recorders).
  bool initialBatchArrived(const std::string& producer) const { return initial_from_.count(producer) != 0; }

  /// Above this wait, progress and records are reported before waiting on.
  static constexpr std::chrono::milliseconds kSlowWait{100};
  /// Least wall time between two observer batches: 30 a second, the viewer's frame rate.
  static constexpr std::chrono::nanoseconds kObserverPeriod{33'333'333};

 private:
  void pollControl();
  void takeRunStart(const Received<climbsim::RunStart>& r);
  void takeStop(const Received<climbsim::Stop>& r);
  /// Once the clock left before any RunStart: the first early Stop of the launcher's run id.
  void takeStopOfUnstartedRun();
  void reportProgress();
  void flushRecords();
  /// Sends the observers' batch (record/ObserverBatch) if one is due, or whatever waits if
  /// `force` (the run ends): at most ObserverFeed's period apart in wall time.
  void flushObservers(bool force);
  /// Sends the initial batch (RecordBatch.initial) if a recorder reads one of our topics.
  void sendInitialRecords();
  void planOutputs();
  void waitUntil(const std::function<bool()>& condition, std::chrono::steady_clock::time_point deadline,
                 const std::string& what);
  void announceReady();
  void awaitRunStart(std::chrono::steady_clock::time_point deadline);
  void armDataEndpoints(std::chrono::steady_clock::time_point deadline);
  /// Throws RetryableStartError if the handshake with one of `peers` (participant names)
  /// has stalled (DdsContext::kHandshakeStall; exit kExitRetryStart); nothing in an unsecured run.
  void checkHandshakes(const std::vector<std::string>& peers) const;
  void sendDone(std::uint64_t step, climbsim::StepDoneKind kind, const std::string& message);
  int exitCodeForStop(const climbsim::Stop& stop) const;
  void failRun(const std::string& message);
  /// Waits (up to kFailureLinger) for the clock's Stop after reporting an end.
  void awaitStop();

  ParticipantOptions options_;
  Notifier notifier_;
  std::unique_ptr<DdsContext> dds_;
  std::unique_ptr<Reader<climbsim::StepGrantPubSubType>> grant_reader_;
  std::unique_ptr<Reader<climbsim::RunStartPubSubType>> run_start_reader_;
  std::unique_ptr<Reader<climbsim::StopPubSubType>> stop_reader_;
  std::unique_ptr<Writer<climbsim::StepDonePubSubType>> done_writer_;
  std::unique_ptr<Writer<climbsim::ParticipantReadyPubSubType>> ready_writer_;
  std::unique_ptr<Writer<climbsim::RecordBatchPubSubType>> batch_writer_;
  std::unique_ptr<Writer<climbsim::RecordBatchPubSubType>> observer_writer_;  ///< record/ObserverBatch
  std::unique_ptr<Reader<climbsim::RecordBatchPubSubType>> batch_reader_;  ///< recorders only
  std::vector<std::unique_ptr<detail::InputPort>> inputs_;
  std::vector<std::unique_ptr<detail::OutputPort>> outputs_;
  std::vector<std::unique_ptr<detail::RecordedPort>> recorded_;

  /// A consumer of one of our topics: its schedule and the lag it reads with.
  struct Consumer {
    Schedule schedule;
    InputLag lag;
  };
  std::map<std::string, std::vector<Consumer>> consumers_;  ///< by output topic
  std::set<std::string> recorded_outputs_;                  ///< our topics a recorder reads
  std::vector<std::string> recorder_names_;                 ///< recorders reading any of them

  std::optional<climbsim::RunStart> run_start_;
  /// The run id the launcher gave (CLIMBSIM_RUN_ID): a RunStart or Stop of another is not ours.
  std::optional<std::uint64_t> expected_run_id_;
  std::optional<ParticipantId> clock_id_;  ///< the DDS participant that sent our RunStart
  std::map<std::string, ParticipantId> identities_;  ///< roster participant -> DDS participant
  std::map<std::string, std::vector<detail::ProducerIdentity>> producer_ids_;  ///< by topic
  /// Stops that came before RunStart, even of this run's id: judged once RunStart binds the
  /// clock, or, if the clock leaves without one, the first of this run's id is the run's end
  /// (the clock stopped it before starting it). The run id is no secret once the clock has
  /// published RunStart: an outsider reads it there and may forge a Stop that reaches us
  /// before our own copy of the RunStart does.
  std::vector<Received<climbsim::Stop>> early_stops_;
  SenderLog dropped_;
  std::optional<climbsim::Stop> stop_;
  bool clock_seen_ = false;
  bool clock_lost_ = false;
  std::uint64_t end_step_ = 0;
  std::uint64_t horizon_ = 0;   ///< every due step below it may be computed
  std::uint64_t progress_ = 0;  ///< every due step below it is done
  std::uint64_t acked_ = 0;     ///< progress last acknowledged to the clock
  std::uint64_t ack_stride_ = 1;
  std::chrono::steady_clock::time_point last_report_{};
  climbsim::RecordBatch batch_;
  ObserverFeed observer_feed_{kObserverPeriod};
  std::map<std::string, std::vector<std::uint8_t>> initial_records_;  ///< our topics' initial states (CDR)
  std::set<std::string> initial_from_;  ///< producers whose initial batch arrived (recorders)
  std::optional<std::uint64_t> current_step_;
  bool fell_reported_ = false;
};

// ---------------------------------------------------------------- templates

namespace detail {

template <class Sample>
void StampQueues<Sample>::push(const std::string& source, Sample&& sample) {
  auto& queue = by_source_[source];
  queue.push_back(std::move(sample));
  // A consumer is at most a window behind; far more than that is a producer gone wrong.
  constexpr std::size_t kMaxQueued = 4096;
  while (queue.size() > kMaxQueued) {
    queue.pop_front();
  }
}

template <class Sample>
std::vector<Sample> StampQueues<Sample>::takeAll() {
  std::vector<Sample> out;
  for (auto& [source, queue] : by_source_) {
    for (auto& sample : queue) out.push_back(std::move(sample));
    queue.clear();
  }
  return out;
}

template <class Sample>
template <class DrainFn, class BeforeFirstFn>
std::vector<Sample> StampQueues<Sample>::get(LockstepParticipant& owner, const std::string& topic,
                                             std::uint64_t step, InputLag lag, DrainFn drain,
                                             BeforeFirstFn before_first, const std::vector<std::string>& only) {
  std::vector<Sample> out;
  for (const auto& [producer, schedule] : owner.producersOf(topic)) {
    if (!only.empty() && std::find(only.begin(), only.end(), producer) == only.end()) {
      continue;
    }
    const auto stamp = schedule.lastDueBefore(lag == InputLag::kSameStep ? step + 1 : step);
    if (!stamp) {
      if (std::optional<Sample> initial = before_first(producer)) {
        out.push_back(std::move(*initial));
      }
      continue;
    }
    while (true) {
      const auto seen = owner.notifier().generation();
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
        throw std::runtime_error("topic '" + topic + "': needed the sample of '" + producer + "' stamped " +
                                 std::to_string(*stamp) + " but the next one is stamped " +
                                 std::to_string(queue.front().step()));
      }
      owner.waitForNews(seen);
    }
  }
  return out;
}

}  // namespace detail

template <class PubSubT>
StampedInput<PubSubT>::StampedInput(LockstepParticipant& owner, const std::string& topic, InputLag lag,
                                    std::vector<std::string> from)
    : owner_(owner),
      topic_(topic),
      lag_(lag),
      from_(std::move(from)),
      reader_(owner.dds(), topic, qos::kStepData, owner.notifier(), from_) {}

template <class PubSubT>
void StampedInput<PubSubT>::drain() {
  if (producers_ == nullptr && (producers_ = owner_.producerIdentities(topic_)) == nullptr) {
    return;  // before the run start nobody's identity is known: the samples wait in the reader
  }
  for (auto& received : reader_.take()) {
    const char* source = received.data.source().c_str();
    if (!detail::sentByProducer(*producers_, source, received.sender)) {
      owner_.dropForeign(topic_, received.writer,
                         "claims to be '" + std::string(source) + "' from DDS participant " +
                             participantIdHex(received.sender) + ", not a producer of the topic on the roster");
      continue;
    }
    queues_.push(source, std::move(received.data));
  }
}

template <class PubSubT>
std::vector<typename PubSubT::type> StampedInput<PubSubT>::get(const StepContext& ctx) {
  return queues_.get(
      owner_, topic_, ctx.step, lag_, [this] { drain(); }, [](const std::string&) { return std::optional<Sample>(); },
      from_);
}

template <class PubSubT>
typename PubSubT::type RecordedInput<PubSubT>::decode(const std::string& source, const std::vector<std::uint8_t>& cdr) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
  std::copy(cdr.begin(), cdr.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(cdr.size());
  Sample sample;
  if (!type_.deserialize(&payload, &sample)) {
    throw std::runtime_error("record batch of '" + source + "': a sample of topic '" + topic_ + "' does not decode");
  }
  return sample;
}

template <class PubSubT>
void RecordedInput<PubSubT>::accept(const std::string& source, const std::vector<std::uint8_t>& cdr) {
  queues_.push(source, decode(source, cdr));
}

template <class PubSubT>
void RecordedInput<PubSubT>::acceptInitial(const std::string& source, const std::vector<std::uint8_t>& cdr) {
  initial_.insert_or_assign(source, decode(source, cdr));
}

template <class PubSubT>
std::vector<typename PubSubT::type> RecordedInput<PubSubT>::get(const StepContext& ctx) {
  return queues_.get(
      owner_, topic_, ctx.step, InputLag::kOneStep, [this] { owner_.drainRecords(); },
      [this](const std::string& producer) -> std::optional<Sample> {
        // The initial batch comes at the producer's run start, before any of its steps.
        while (!owner_.initialBatchArrived(producer)) {
          const auto seen = owner_.notifier().generation();
          owner_.drainRecords();
          if (owner_.initialBatchArrived(producer)) break;
          owner_.waitForNews(seen);
        }
        const auto found = initial_.find(producer);
        return found == initial_.end() ? std::nullopt : std::optional<Sample>(found->second);
      });
}

template <class PubSubT>
std::vector<typename PubSubT::type> RecordedInput<PubSubT>::takeArrived() {
  owner_.drainRecords();
  return queues_.takeAll();
}

template <class PubSubT>
StampedOutput<PubSubT>::StampedOutput(LockstepParticipant& owner, const std::string& topic)
    : owner_(owner), writer_(owner.dds(), topic, qos::kStepData, owner.notifier(), owner.name()) {}

template <class PubSubT>
void StampedOutput<PubSubT>::recordInitial(Sample& sample) {
  sample.source(owner_.name());
  sample.step(0);
  sample.t_ns(0);
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type_.getSerializedSizeProvider(&sample)());
  if (!type_.serialize(&sample, &payload)) {
    throw std::runtime_error("topic '" + topic() + "': the initial state does not serialise for its record batch");
  }
  owner_.recordInitial(topic(), payload);
}

template <class PubSubT>
void StampedOutput<PubSubT>::write(const StepContext& ctx, Sample& sample) {
  if (owner_.currentStep() != ctx.step) {
    throw std::logic_error("topic '" + topic() + "': written outside its step " + std::to_string(ctx.step));
  }
  sample.source(owner_.name());
  sample.step(ctx.step);
  sample.t_ns(ctx.t_ns);
  if (owner_.isRecorded(topic())) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(type_.getSerializedSizeProvider(&sample)());
    if (!type_.serialize(&sample, &payload)) {
      throw std::runtime_error("topic '" + topic() + "': a sample does not serialise for its record batch");
    }
    owner_.record(topic(), ctx.step, payload);
  }
  if (owner_.stampIsRead(topic(), ctx.step)) {
    writer_.write(sample);
  }
}

}  // namespace climbsim
