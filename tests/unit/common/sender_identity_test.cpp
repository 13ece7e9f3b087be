// Who sent a sample: GUID prefixes as text and the producer check of every
// stamped sample.

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "climbsim/dds_context.hpp"
#include "climbsim/lockstep_participant.hpp"
#include "climbsim/sender_identity.hpp"

namespace climbsim {
namespace {

ParticipantId prefix(std::uint8_t first) {
  ParticipantId id;
  for (unsigned i = 0; i < ParticipantId::size; ++i) id.value[i] = static_cast<std::uint8_t>(first + 17 * i);
  return id;
}

TEST(SenderIdentity, AWritersKeyIsTheTextFastDdsGivesItsGuid) {
  std::mt19937 random(11);
  for (int n = 0; n < 2000; ++n) {
    eprosima::fastrtps::rtps::GUID_t guid;
    for (auto& byte : guid.guidPrefix.value) byte = static_cast<std::uint8_t>(random() % (n % 3 == 0 ? 16 : 256));
    for (auto& byte : guid.entityId.value) byte = static_cast<std::uint8_t>(random() % (n % 2 == 0 ? 16 : 256));
    std::ostringstream fast_dds;
    fast_dds << guid;
    ASSERT_EQ(writerKey(eprosima::fastrtps::rtps::InstanceHandle_t(guid)), fast_dds.str());
  }
  std::ostringstream unknown;
  unknown << eprosima::fastrtps::rtps::c_Guid_Unknown;
  EXPECT_EQ(writerKey(eprosima::fastrtps::rtps::InstanceHandle_t(eprosima::fastrtps::rtps::c_Guid_Unknown)),
            unknown.str());
}

TEST(SenderIdentity, APrefixSurvivesItsHexText) {
  const ParticipantId id = prefix(0x0f);
  const std::string hex = participantIdHex(id);
  EXPECT_EQ(hex.size(), 24u);
  EXPECT_EQ(hex.substr(0, 4), "0f20");
  const auto back = participantIdFromHex(hex);
  ASSERT_TRUE(back.has_value());
  EXPECT_TRUE(*back == id);
  EXPECT_TRUE(participantIdFromHex("0F20" + hex.substr(4)).has_value()) << "upper case is hex too";
}

TEST(SenderIdentity, TextThatIsNotAPrefixIsRefused) {
  EXPECT_FALSE(participantIdFromHex("").has_value());
  EXPECT_FALSE(participantIdFromHex("0f").has_value());
  EXPECT_FALSE(participantIdFromHex(std::string(23, '0') + "g").has_value());
  EXPECT_FALSE(participantIdFromHex(std::string(26, '0')).has_value());
}

TEST(SenderIdentity, OnlyTheBoundParticipantOfAProducerIsBelieved) {
  const std::vector<detail::ProducerIdentity> producers = {{"controller", prefix(1)}, {"planner", prefix(2)}};
  EXPECT_TRUE(detail::sentByProducer(producers, "controller", prefix(1)));
  EXPECT_TRUE(detail::sentByProducer(producers, "planner", prefix(2)));
  EXPECT_FALSE(detail::sentByProducer(producers, "controller", prefix(3))) << "another DDS participant";
  EXPECT_FALSE(detail::sentByProducer(producers, "controller", prefix(2))) << "a producer claiming another's name";
  EXPECT_FALSE(detail::sentByProducer(producers, "thermo", prefix(1))) << "not a producer of the topic";
  EXPECT_FALSE(detail::sentByProducer({}, "controller", prefix(1)));
}

TEST(SenderIdentity, DroppedSamplesAreCountedEach) {
  SenderLog log("test");
  log.drop("t", "w1", "why");
  log.drop("t", "w1", "why");
  log.drop("t", "w2", "why");
  EXPECT_EQ(log.dropped(), 3u);
}

}  // namespace
}  // namespace climbsim
