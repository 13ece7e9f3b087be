#include "climbsim/dds_context.hpp"

#include <fastdds/rtps/common/Guid.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include <algorithm>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>

#include "climbsim/dds_discovery.hpp"
#include "climbsim/dds_security.hpp"
#include "climbsim/errors.hpp"

#include <spdlog/spdlog.h>

namespace climbsim {

namespace dds = eprosima::fastdds::dds;

std::string writerKey(const eprosima::fastrtps::rtps::InstanceHandle_t& handle) {
  // Every received sample is keyed so: written directly, not through Fast DDS's operator<<
  // (three string streams a call), with the same characters.
  const eprosima::fastrtps::rtps::GUID_t guid = eprosima::fastrtps::rtps::iHandle2GUID(handle);
  if (guid == eprosima::fastrtps::rtps::c_Guid_Unknown) return "|GUID UNKNOWN|";
  static constexpr char kHex[] = "0123456789abcdef";
  std::string key;
  key.reserve(48);
  for (int i = 0; i < 12; ++i) {  // the prefix: two hex digits a byte, dot-separated
    const unsigned byte = guid.guidPrefix.value[i];
    if (i > 0) key += '.';
    key += kHex[byte >> 4];
    key += kHex[byte & 15];
  }
  key += '|';
  for (int i = 0; i < 4; ++i) {  // the entity id: hex without leading zeros, dot-separated
    const unsigned byte = guid.entityId.value[i];
    if (i > 0) key += '.';
    if (byte >= 16) key += kHex[byte >> 4];
    key += kHex[byte & 15];
  }
  return key;
}

/// Logs the remote participants the local one loses to their lease or refuses to
/// authenticate, by name, and passes every callback on to the owner's listener.
class DdsContext::ParticipantWatch : public dds::DomainParticipantListener {
 public:
  /// `secured`: the participant authenticates the others (pending handshakes are tracked).
  ParticipantWatch(dds::DomainParticipantListener* next, bool secured) : next_(next), secured_(secured) {}

  void on_participant_discovery(dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using Info = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
    if (info.status == Info::DROPPED_PARTICIPANT) {
      spdlog::info("DDS participant '{}' dropped: no announcement from it within its lease",
                   info.info.m_participantName.c_str());
    }
    if (secured_) {
      // Fast DDS 2.9 tells of a participant when its announcement arrives, before the
      // handshake: it is pending until the handshake ends either way.
      std::lock_guard<std::mutex> lock(mutex_);
      const auto key = prefixKey(info.info.m_guid);
      if (info.status == Info::DISCOVERED_PARTICIPANT) {
        if (authenticated_.count(key) == 0 && refused_.count(key) == 0) {
          pending_.emplace(key, Pending{info.info.m_participantName.c_str(), std::chrono::steady_clock::now()});
        }
      } else if (info.status == Info::DROPPED_PARTICIPANT || info.status == Info::REMOVED_PARTICIPANT) {
        pending_.erase(key);
      }
    }
    if (next_ != nullptr) next_->on_participant_discovery(participant, std::move(info));
  }

  /// See DdsContext::unauthenticatedPeers.
  std::vector<std::string> pendingOlderThan(std::chrono::steady_clock::duration age) const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> names;
    const auto now = std::chrono::steady_clock::now();
    for (const auto& [key, pending] : pending_) {
      if (now - pending.since >= age) names.push_back(pending.name);
    }
    return names;
  }

  // The rest of the discovery callbacks go to the owner's listener unchanged (the
  // participant's status mask is none: no other callback reaches a participant listener).
  void on_publisher_discovery(dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    if (next_ != nullptr) next_->on_publisher_discovery(participant, std::move(info));
  }
  void on_subscriber_discovery(dds::DomainParticipant* participant,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
    if (next_ != nullptr) next_->on_subscriber_discovery(participant, std::move(info));
  }
  void on_type_discovery(dds::DomainParticipant* participant, const eprosima::fastrtps::rtps::SampleIdentity& request,
                         const eprosima::fastrtps::string_255& topic, const eprosima::fastrtps::types::TypeIdentifier* id,
                         const eprosima::fastrtps::types::TypeObject* object,
                         eprosima::fastrtps::types::DynamicType_ptr type) override {
    if (next_ != nullptr) next_->on_type_discovery(participant, request, topic, id, object, type);
  }
  void on_type_dependencies_reply(dds::DomainParticipant* participant,
                                  const eprosima::fastrtps::rtps::SampleIdentity& request,
                                  const eprosima::fastrtps::types::TypeIdentifierWithSizeSeq& dependencies) override {
    if (next_ != nullptr) next_->on_type_dependencies_reply(participant, request, dependencies);
  }
  void on_type_information_received(dds::DomainParticipant* participant, const eprosima::fastrtps::string_255 topic,
                                    const eprosima::fastrtps::string_255 type,
                                    const eprosima::fastrtps::types::TypeInformation& information) override {
    if (next_ != nullptr) next_->on_type_information_received(participant, topic, type, information);
  }

#if HAVE_SECURITY
  void onParticipantAuthentication(dds::DomainParticipant* participant,
                                   eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override {
    using Auth = eprosima::fastrtps::rtps::ParticipantAuthenticationInfo;
    const auto key = prefixKey(info.guid);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_.erase(key);
      if (info.status == Auth::UNAUTHORIZED_PARTICIPANT) {
        // A refused participant announces itself again every period: it is named once.
        if (refused_.insert(key).second) {
          spdlog::info("DDS participant {} refused: it did not authenticate with the run's CA", key);
        }
      } else {
        authenticated_.insert(key);
      }
    }
    if (next_ != nullptr) next_->onParticipantAuthentication(participant, std::move(info));
  }
#endif

 private:
  struct Pending {
    std::string name;                           ///< the name it announced
    std::chrono::steady_clock::time_point since;  ///< when its announcement arrived
  };
  static std::string prefixKey(const eprosima::fastrtps::rtps::GUID_t& guid) {
    std::ostringstream out;
    out << guid.guidPrefix;
    return out.str();
  }

  dds::DomainParticipantListener* next_;
  const bool secured_;
  mutable std::mutex mutex_;
  std::map<std::string, Pending> pending_;  ///< by GUID prefix: discovered, handshake not ended
  std::set<std::string> authenticated_;     ///< GUID prefixes whose handshake completed
  std::set<std::string> refused_;           ///< GUID prefixes refused (named once)
};

namespace {
void loadQosFileOnce(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (loaded.count(path) != 0) {
    return;
  }
  if (dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(path) !=
      eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    throw ConfigError("QoS file '" + path + "': Fast DDS cannot load it as an XML profile file");
  }
  loaded.insert(path);
}

/// A process that writes images gets a shared-memory segment that holds them
/// (shmSegmentBytes); the QoS file's is sized for small samples.
void sizeSharedMemorySegment(std::size_t largest_sample_bytes, dds::DomainParticipantQos& pqos) {
  if (largest_sample_bytes == 0) return;
  using eprosima::fastdds::rtps::SharedMemTransportDescriptor;
  for (auto& transport : pqos.transport().user_transports) {
    if (const auto shm = std::dynamic_pointer_cast<SharedMemTransportDescriptor>(transport)) {
      auto sized = std::make_shared<SharedMemTransportDescriptor>(*shm);
      const std::size_t bytes = shmSegmentBytes(shm->segment_size(), largest_sample_bytes);
      sized->segment_size(static_cast<uint32_t>(std::min<std::size_t>(bytes, std::numeric_limits<uint32_t>::max())));
      transport = sized;
    }
  }
}
}  // namespace

DdsContext::DdsContext(const DdsSettings& settings, const std::string& participant_name,
                       dds::DomainParticipantListener* listener)
    : settings_(settings) {
  loadQosFileOnce(settings.qos_file);
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantQos pqos;
  if (factory->get_participant_qos_from_profile(qos::kParticipant, pqos) !=
      eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    throw ConfigError("QoS file '" + settings.qos_file + "': no participant profile '" +
                      std::string(qos::kParticipant) + "'");
  }
  pqos.name(participant_name);
  sizeSharedMemorySegment(settings.largest_sample_bytes, pqos);
  if (const auto discovery = unicastDiscoveryFromEnvironment()) {
    applyUnicastDiscovery(*discovery, pqos);
  }
  security_ = securityFilesFromEnvironment(participant_name);
  if (security_) {
    checkSecurityFiles(*security_);
    applySecurity(*security_, pqos);
  }
  watch_ = std::make_unique<ParticipantWatch>(listener, security_.has_value());
  participant_ = factory->create_participant(static_cast<dds::DomainId_t>(settings.domain_id), pqos, watch_.get(),
                                             dds::StatusMask::none());
  if (participant_ == nullptr && security_) {
    throw ConfigError("participant '" + security_->identity + "': Fast DDS refused its DDS Security files (CA '" +
                      security_->ca_cert + "', certificate '" + security_->cert + "', governance '" +
                      security_->governance + "', permissions '" + security_->permissions +
                      "'): a signature or subject does not match the run's CA");
  }
  if (participant_ == nullptr) {
    throw ConfigError("cannot create a DDS participant on domain " + std::to_string(settings.domain_id) +
                      " with the profile '" + std::string(qos::kParticipant) + "' of '" + settings.qos_file + "'");
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    throw std::runtime_error("cannot create a DDS publisher or subscriber");
  }
}

std::vector<std::string> DdsContext::unauthenticatedPeers(std::chrono::steady_clock::duration age) const {
  return watch_->pendingOlderThan(age);
}

std::optional<DdsContext::StalledHandshake> DdsContext::stalledHandshake(const std::string& self,
                                                                         const std::vector<std::string>& peers) const {
  if (!security_) return std::nullopt;
  for (const auto& stalled : unauthenticatedPeers(kHandshakeStall)) {
    if (stalled != self && std::find(peers.begin(), peers.end(), stalled) != peers.end()) {
      return StalledHandshake{stalled, "the DDS Security handshake between '" + self + "' and '" + stalled +
                                           "' has not ended " + std::to_string(kHandshakeStall.count()) +
                                           " s after they discovered each other (Fast DDS 2.9.1 leaves a pair of "
                                           "participants so now and then; no step was computed: the run can start "
                                           "again)"};
    }
  }
  return std::nullopt;
}

DdsContext::~DdsContext() {
  if (participant_ != nullptr) {
    participant_->set_listener(nullptr);
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
}

int DdsContext::historyDepth(const std::string& profile) const {
  dds::DataWriterQos wqos;
  dds::DataReaderQos rqos;
  if (publisher_->get_datawriter_qos_from_profile(profile + ".writer", wqos) !=
          eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK ||
      subscriber_->get_datareader_qos_from_profile(profile + ".reader", rqos) !=
          eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
    throw ConfigError("QoS file '" + settings_.qos_file + "': no writer and reader profiles '" + profile + "'");
  }
  auto depth = [](const auto& history) {
    return history.kind == dds::KEEP_ALL_HISTORY_QOS ? std::numeric_limits<int>::max() : history.depth;
  };
  return std::min(depth(wqos.history()), depth(rqos.history()));
}

void DdsContext::refused(const char* what, const std::string& topic_name, const std::string& profile) const {
  if (security_) {
    throw ConfigError("participant '" + security_->identity + "': its DDS Security permissions '" +
                      security_->permissions + "' do not let it " + (std::string(what) == "writer" ? "publish" : "subscribe to") +
                      " topic '" + topic_name + "'");
  }
  throw std::runtime_error("cannot create a " + std::string(what) + " of topic '" + topic_name +
                           "' with QoS profile '" + profile + "." + what + "'");
}

dds::Topic* DdsContext::topicFor(const std::string& name, dds::TopicDataType* (*make)()) {
  auto found = topics_.find(name);
  if (found != topics_.end()) {
    return found->second;
  }
  dds::TypeSupport type(make());
  const std::string type_name = type.get_type_name();
  if (participant_->find_type(type_name).empty()) {
    type.register_type(participant_);
  }
  auto* topic = participant_->create_topic(name, type_name, dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr && security_) {
    throw ConfigError("participant '" + security_->identity + "': its DDS Security permissions '" +
                      security_->permissions + "' do not name topic '" + name + "'");
  }
  if (topic == nullptr) {
    throw std::runtime_error("cannot create topic '" + name + "' of type '" + type_name + "'");
  }
  topics_.emplace(name, topic);
  return topic;
}

dds::Publisher* DdsContext::producerPublisher(const std::string& producer) {
  auto found = producer_publishers_.find(producer);
  if (found != producer_publishers_.end()) {
    return found->second;
  }
  dds::PublisherQos qos = dds::PUBLISHER_QOS_DEFAULT;
  qos.partition().push_back("");
  qos.partition().push_back(producerPartition(producer).c_str());
  auto* publisher = participant_->create_publisher(qos);
  if (publisher == nullptr) {
    throw std::runtime_error("cannot create the DDS publisher of partition '" + producerPartition(producer) + "'");
  }
  producer_publishers_.emplace(producer, publisher);
  return publisher;
}

dds::Subscriber* DdsContext::subscriberFrom(const std::vector<std::string>& producers) {
  if (producers.empty()) {
    return subscriber_;
  }
  auto found = subscribers_from_.find(producers);
  if (found != subscribers_from_.end()) {
    return found->second;
  }
  dds::SubscriberQos qos = dds::SUBSCRIBER_QOS_DEFAULT;
  for (const auto& producer : producers) {
    qos.partition().push_back(producerPartition(producer).c_str());
  }
  auto* subscriber = participant_->create_subscriber(qos);
  if (subscriber == nullptr) {
    throw std::runtime_error("cannot create a DDS subscriber of the partitions of " + producers.front() + "...");
  }
  subscribers_from_.emplace(producers, subscriber);
  return subscriber;
}

}  // namespace climbsim
