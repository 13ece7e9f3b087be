#pragma once
/// @file
/// One Fast DDS participant configured from the climbsim QoS file, and typed
/// readers and writers whose listeners wake a Notifier.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <atomic>
#include <cstdint>
#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "climbsim/dds_security.hpp"
#include "climbsim/dds_settings.hpp"
#include "climbsim/notifier.hpp"
#include "climbsim/sender_identity.hpp"

namespace climbsim {

/// QoS profile names in deploy/qos/climbsim.xml.
namespace qos {
inline constexpr const char* kParticipant = "climbsim.participant";
inline constexpr const char* kControl = "climbsim.control";      ///< grant, done, control
inline constexpr const char* kLatched = "climbsim.latched";      ///< ready, run start, stop
inline constexpr const char* kStepData = "climbsim.step_data";   ///< stamped lockstep data
inline constexpr const char* kObserver = "climbsim.observer";    ///< SimTime, viewer images
inline constexpr const char* kPictures = "climbsim.pictures";    ///< pictures a run keeps (reliable)
inline constexpr const char* kRecord = "climbsim.record";        ///< record batches (reliable, keep all)
/// record batches read by observers (best effort, latest per producer)
inline constexpr const char* kRecordObserver = "climbsim.record_observer";
}  // namespace qos

/// A stable text key for the writer behind a sample or a status (its GUID).
std::string writerKey(const eprosima::fastrtps::rtps::InstanceHandle_t& handle);

/// The DomainParticipant of one process and the topics it uses. Not copyable.
class DdsContext {
 public:
  /// Loads the QoS file (once per process) and creates the participant on the domain.
  /// Throws ConfigError if the file does not load or the participant cannot be created.
  /// `listener` (optional, outliving the context) hears of the remote participants from
  /// the start (on_participant_discovery: the clock checks who sends ClockControl).
  /// A remote participant dropped for its lease is logged (info) with its name, one refused by
  /// authentication once with its GUID prefix.
  DdsContext(const DdsSettings& settings, const std::string& participant_name,
             eprosima::fastdds::dds::DomainParticipantListener* listener = nullptr);
  ~DdsContext();
  DdsContext(const DdsContext&) = delete;
  DdsContext& operator=(const DdsContext&) = delete;

  /// Registers the type (once) and creates the topic (once).
  template <class PubSubT>
  eprosima::fastdds::dds::Topic* topic(const std::string& name) {
    return topicFor(name, []() -> eprosima::fastdds::dds::TopicDataType* { return new PubSubT(); });
  }

  eprosima::fastdds::dds::Publisher* publisher() { return publisher_; }
  eprosima::fastdds::dds::Subscriber* subscriber() { return subscriber_; }
  /// The DDS partition only the stamped writers of roster member `producer` are in (besides
  /// the default one): a reader in it gets that producer's samples and nobody else's.
  static std::string producerPartition(const std::string& producer) { return "climbsim.from." + producer; }
  /// The publisher of `producer`'s stamped writers: partitions "" (every ordinary reader)
  /// and producerPartition(producer). Created on first use.
  eprosima::fastdds::dds::Publisher* producerPublisher(const std::string& producer);
  /// The subscriber whose readers match only the writers of `producers` (their partitions);
  /// subscriber() when `producers` is empty. Created on first use.
  eprosima::fastdds::dds::Subscriber* subscriberFrom(const std::vector<std::string>& producers);
  eprosima::fastdds::dds::DomainParticipant* participant() { return participant_; }
  const DdsSettings& settings() const { return settings_; }
  /// This process's identity on the domain: the GUID prefix of its DDS participant.
  ParticipantId id() const { return participant_->guid().guidPrefix; }

  /// History depth (KEEP_LAST) of a profile's writer and reader, the smaller of the two;
  /// what bounds how many stamped samples a producer may be ahead of a consumer.
  int historyDepth(const std::string& profile) const;

  /// The DDS Security files this participant loaded; nothing when the run is not secured.
  const std::optional<SecurityFiles>& security() const { return security_; }

  /// In a secured run, the names (as they announce themselves) of the remote participants
  /// discovered at least `age` ago whose DDS Security handshake with this one has neither
  /// completed nor failed; empty in an unsecured run. Fast DDS 2.9.1 leaves a pair of
  /// participants in that state now and then (4 of 15, then 5 of 30 secured starts of 7
  /// participants here): neither ever matches the other's readers and writers. A handshake normally
  /// completes within a few hundred milliseconds of discovery.
  std::vector<std::string> unauthenticatedPeers(std::chrono::steady_clock::duration age) const;

  /// A DDS Security handshake not ended this long after discovery has stalled (a handshake
  /// takes well under a second, and Fast DDS resends a lost message every second).
  static constexpr std::chrono::seconds kHandshakeStall{5};

  /// A stalled handshake between this participant and a peer it needs.
  struct StalledHandshake {
    std::string peer;    ///< the peer's participant name
    std::string reason;  ///< one line naming the pair, for the start given up
  };

  /// The first of `peers` (participant names) whose handshake with this participant, named
  /// `self`, has stalled (kHandshakeStall); nothing if none has, and in an unsecured run. The
  /// start is then given up (exit kExitRetryStart): nothing was computed, it can start again.
  std::optional<StalledHandshake> stalledHandshake(const std::string& self, const std::vector<std::string>& peers) const;

  /// Throws for a reader or writer ("reader", "writer") Fast DDS did not create: in a secured
  /// run a ConfigError naming the participant and its permissions file (exit 2 before step 0),
  /// else a runtime_error naming the topic and the profile.
  [[noreturn]] void refused(const char* what, const std::string& topic_name, const std::string& profile) const;

  /// Samples taken by this process's readers so far (each one a delivery).
  std::uint64_t deliveries() const { return deliveries_.load(); }
  /// Counts `n` more deliveries (Reader::take).
  void countDeliveries(std::uint64_t n) { deliveries_.fetch_add(n, std::memory_order_relaxed); }

 private:
  eprosima::fastdds::dds::Topic* topicFor(const std::string& name,
                                          eprosima::fastdds::dds::TopicDataType* (*make)());

  class ParticipantWatch;

  DdsSettings settings_;
  std::optional<SecurityFiles> security_;
  std::unique_ptr<ParticipantWatch> watch_;  ///< declared before participant_: outlives it
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::map<std::string, eprosima::fastdds::dds::Publisher*> producer_publishers_;
  std::map<std::vector<std::string>, eprosima::fastdds::dds::Subscriber*> subscribers_from_;
  std::atomic<std::uint64_t> deliveries_{0};
};

/// The remote endpoints a reader or writer has matched, kept from its matching callbacks
/// (Fast DDS 2.9 does not implement get_matched_publications/subscriptions).
///
/// Each callback carries the current count, the change since the status was last read and the
/// handle of the last endpoint matched or unmatched. Fast DDS reads (and so resets) the status
/// just before each callback; nothing else may read it (matchedWriters/matchedReaders answer
/// from here), or a callback would see a change of 0 and its endpoint would be lost. Two
/// matches on two threads at once can still fold into one callback (a change of 2 and one
/// handle): the handles then no longer add up to the count, and participants() says it does
/// not know rather than name too few or too many.
class MatchedEndpoints {
 public:
  using Handle = eprosima::fastrtps::rtps::InstanceHandle_t;

  /// One matching callback's status: `count` endpoints matched now, `change` since the last
  /// one, `last` the endpoint that changed.
  void update(int count, int change, const Handle& last) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (change > 0) handles_.insert(last);
    if (change < 0) handles_.erase(last);
    complete_ = complete_ && (change == 1 || change == -1) && handles_.size() == static_cast<std::size_t>(count);
    count_ = count;
  }
  /// Endpoints matched now.
  int count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  /// The DDS participants of the endpoints matched now, one per endpoint; nothing if a
  /// callback folded two events (from then on: which one was lost is not known).
  std::optional<std::vector<ParticipantId>> participants() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!complete_) return std::nullopt;
    std::vector<ParticipantId> out;
    out.reserve(handles_.size());
    for (const auto& handle : handles_) out.push_back(eprosima::fastrtps::rtps::iHandle2GUID(handle).guidPrefix);
    return out;
  }

 private:
  mutable std::mutex mutex_;
  std::set<Handle> handles_;
  int count_ = 0;
  bool complete_ = true;
};

/// A sample and the writer it came from.
template <class T>
struct Received {
  T data;
  std::string writer;  ///< writerKey() of the sending DataWriter
  ParticipantId sender;  ///< GUID prefix of the DDS participant of that writer
};

/// A change in the liveliness or matching of a remote writer seen by a reader.
struct WriterLost {
  std::string writer;  ///< writerKey() of the writer that is no longer alive or matched
  bool liveliness;     ///< true: liveliness lost; false: unmatched (its process left)
  ParticipantId sender;  ///< GUID prefix of that writer's DDS participant
};

/// A DataReader of PubSubT::type. Listener callbacks only queue and notify; the owner
/// drains the queue on its own thread.
template <class PubSubT>
class Reader : private eprosima::fastdds::dds::DataReaderListener {
 public:
  using Sample = typename PubSubT::type;

  /// A reader of `topic_name`, of the samples of the writers of `only_from` alone if that is
  /// not empty (DdsContext::subscriberFrom: the others' samples are never sent here).
  Reader(DdsContext& dds, const std::string& topic_name, const std::string& profile, Notifier& notifier,
         const std::vector<std::string>& only_from = {})
      : notifier_(notifier), dds_(dds), subscriber_(dds.subscriberFrom(only_from)) {
    auto* topic = dds.topic<PubSubT>(topic_name);
    reader_ = subscriber_->create_datareader_with_profile(topic, profile + ".reader", this,
                                                          eprosima::fastdds::dds::StatusMask::all());
    if (reader_ == nullptr) {
      dds.refused("reader", topic_name, profile);
    }
    const auto& history = reader_->get_qos().history();
    if (history.kind == eprosima::fastdds::dds::KEEP_LAST_HISTORY_QOS && history.depth > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      per_writer_depth_ = static_cast<std::size_t>(history.depth);
    }
  }
  ~Reader() override {
    reader_->set_listener(nullptr);
    subscriber_->delete_datareader(reader_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  /// Every valid sample received since the last call, oldest first.
  std::vector<Received<Sample>> take() {
    std::vector<Received<Sample>> out;
    // Cheap when nothing came: the lockstep polls every reader several times a step.
    // Cleared before taking, so a sample arriving meanwhile sets it again.
    if (!data_pending_.exchange(false)) {
      return out;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    out.reserve(queue_.size());
    for (auto& entry : queue_) out.push_back(std::move(entry.received));
    queue_.clear();
    per_writer_.clear();
    dds_.countDeliveries(out.size());
    return out;
  }

  /// Writers lost since the last call.
  std::vector<WriterLost> takeLost() {
    if (!lost_pending_.exchange(false)) {
      return {};
    }
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<WriterLost> out;
    out.swap(lost_);
    return out;
  }

  /// Number of writers currently matched.
  int matchedWriters() const { return matched_.count(); }

  /// The DDS participants (GUID prefixes) of the writers matched now, one per writer, or
  /// nothing when the matching events did not tell them all (MatchedEndpoints). Who to wait
  /// for before a run starts: a count would let any writer of the topic (an outsider's, a
  /// tool's) stand in for a producer whose writer has not matched yet, and a sample written
  /// before the match is lost to this VOLATILE reader.
  std::optional<std::vector<ParticipantId>> matchedParticipants() const { return matched_.participants(); }

 private:
  /// Takes the samples at once, on the thread that delivered them: the DDS
  /// history of a topic is one KEEP_LAST queue for all its writers, so samples left there
  /// until the owner's next take() could be pushed out by another writer's flood (an outsider
  /// writing 41 forged ValveCommand samples evicted the controller's before thermo, loaded,
  /// took and dropped them, and thermo then waited for them until the watchdog ended the
  /// run). Here each writer keeps at most the history depth of its own samples. mutex_ is
  /// never held while calling into DDS (Fast DDS calls this holding the reader's own lock).
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    std::vector<Queued> taken;
    eprosima::fastdds::dds::SampleInfo info;
    Sample sample;
    while (reader->take_next_sample(&sample, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        const auto& handle = info.publication_handle;
        taken.push_back(
            {{std::move(sample), writerKey(handle), eprosima::fastrtps::rtps::iHandle2GUID(handle).guidPrefix}, handle});
        sample = Sample();
      }
    }
    if (taken.empty()) {
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& entry : taken) {
        std::size_t& held = per_writer_[entry.handle];
        if (per_writer_depth_ > 0 && held >= per_writer_depth_) {
          // This writer's oldest sample goes, not another writer's.
          for (auto it = queue_.begin(); it != queue_.end(); ++it) {
            if (it->handle == entry.handle) {
              queue_.erase(it);
              --held;
              break;
            }
          }
        }
        queue_.push_back(std::move(entry));
        ++held;
      }
    }
    data_pending_ = true;
    notifier_.notify();
  }

  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& status) override {
    matched_.update(status.current_count, status.current_count_change, status.last_publication_handle);
    if (status.current_count_change < 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      lost_.push_back({writerKey(status.last_publication_handle), false,
                       eprosima::fastrtps::rtps::iHandle2GUID(status.last_publication_handle).guidPrefix});
      lost_pending_ = true;
    }
    notifier_.notify();
  }

  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& status) override {
    if (status.not_alive_count_change > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      lost_.push_back({writerKey(status.last_publication_handle), true,
                       eprosima::fastrtps::rtps::iHandle2GUID(status.last_publication_handle).guidPrefix});
      lost_pending_ = true;
    }
    notifier_.notify();
  }

  Notifier& notifier_;
  DdsContext& dds_;
  eprosima::fastdds::dds::Subscriber* subscriber_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::mutex mutex_;
  std::vector<WriterLost> lost_;
  std::atomic<bool> lost_pending_{false};
  std::atomic<bool> data_pending_{false};  ///< queue_ may hold samples
  /// A taken sample and its writer's handle.
  struct Queued {
    Received<Sample> received;
    eprosima::fastrtps::rtps::InstanceHandle_t handle;
  };
  std::deque<Queued> queue_;  ///< taken from DDS, not yet by take(); oldest first (mutex_)
  std::map<eprosima::fastrtps::rtps::InstanceHandle_t, std::size_t> per_writer_;  ///< samples in queue_ (mutex_)
  std::size_t per_writer_depth_ = 0;  ///< KEEP_LAST depth of the reader, 0 before it is known (mutex_)
  MatchedEndpoints matched_;  ///< the writers matched now
};

/// A DataWriter of PubSubT::type whose matching wakes a Notifier.
template <class PubSubT>
class Writer : private eprosima::fastdds::dds::DataWriterListener {
 public:
  using Sample = typename PubSubT::type;

  /// A writer of `topic_name`; with `producer` given, in that producer's partition too
  /// (DdsContext::producerPublisher), so that readers can select it.
  Writer(DdsContext& dds, const std::string& topic_name, const std::string& profile, Notifier& notifier,
         const std::string& producer = "")
      : notifier_(notifier),
        publisher_(producer.empty() ? dds.publisher() : dds.producerPublisher(producer)),
        topic_name_(topic_name) {
    auto* topic = dds.topic<PubSubT>(topic_name);
    writer_ = publisher_->create_datawriter_with_profile(topic, profile + ".writer", this,
                                                         eprosima::fastdds::dds::StatusMask::all());
    if (writer_ == nullptr) {
      dds.refused("writer", topic_name, profile);
    }
  }
  ~Writer() override {
    writer_->set_listener(nullptr);
    publisher_->delete_datawriter(writer_);
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Writes one sample; throws if Fast DDS refuses it for longer than kWriteRetryLimit.
  ///
  /// Fast DDS 2.9 now and then refuses a write at once with RETCODE_TIMEOUT when the oldest
  /// sample of a full KEEP_LAST history cannot be removed at that moment (seen 3 times in 60
  /// runs of a 2000-step lockstep test on a loaded machine). It has then released the new
  /// change without adding it (DataWriterImpl::perform_create_new_change), so writing again
  /// cannot duplicate the sample: the write is retried every millisecond, up to the limit.
  void write(Sample& sample) {
    using eprosima::fastrtps::types::ReturnCode_t;
    const auto give_up = std::chrono::steady_clock::now() + kWriteRetryLimit;
    for (;;) {
      const auto code = writer_->write(&sample, eprosima::fastrtps::rtps::InstanceHandle_t());
      if (code == ReturnCode_t::RETCODE_OK) {
        return;
      }
      if (code != ReturnCode_t::RETCODE_TIMEOUT || std::chrono::steady_clock::now() >= give_up) {
        throw std::runtime_error("writing to topic '" + topic_name_ + "' failed (Fast DDS return code " +
                                 std::to_string(code()) + ")");
      }
      ++write_retries_;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  /// How long write() retries a refused sample (as the profiles' max_blocking_time).
  static constexpr std::chrono::milliseconds kWriteRetryLimit{1000};

  /// Writes that were refused once and retried (diagnostics).
  std::uint64_t writeRetries() const { return write_retries_; }

  /// Number of readers currently matched.
  int matchedReaders() const { return matched_.count(); }

  /// The DDS participants (GUID prefixes) of the readers matched now, one per reader, or
  /// nothing when the matching events did not tell them all (see Reader::matchedParticipants:
  /// a consumer whose reader matches after a sample was written never gets that sample).
  std::optional<std::vector<ParticipantId>> matchedParticipants() const { return matched_.participants(); }

  const std::string& topicName() const { return topic_name_; }

  /// Waits until every matched reliable reader acknowledged what was written; false on
  /// timeout. Not for the lockstep's hot path (it may wait for a heartbeat period).
  bool waitAcknowledged(std::chrono::milliseconds timeout) {
    const auto secs = std::chrono::duration_cast<std::chrono::seconds>(timeout);
    const auto nanos = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout - secs);
    return writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(
               static_cast<std::int32_t>(secs.count()), static_cast<std::uint32_t>(nanos.count()))) ==
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK;
  }

 private:
  void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                              const eprosima::fastdds::dds::PublicationMatchedStatus& status) override {
    matched_.update(status.current_count, status.current_count_change, status.last_subscription_handle);
    notifier_.notify();
  }

  Notifier& notifier_;
  eprosima::fastdds::dds::Publisher* publisher_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  std::string topic_name_;
  MatchedEndpoints matched_;  ///< the readers matched now
  std::uint64_t write_retries_ = 0;
};

}  // namespace climbsim
