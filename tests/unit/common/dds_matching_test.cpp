// Readers and writers name the DDS participants of the endpoints they have matched, so that a
// participant can wait for its producers and consumers by who they are (the lockstep's arming)
// rather than count endpoints, which an outsider's writer or reader would satisfy. Real Fast
// DDS participants on a domain of their own.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "climbsim/dds_context.hpp"
#include "climbsim/dds_settings.hpp"
#include "climbsim/domain_lease.hpp"
#include "climbsim/notifier.hpp"
#include "testingPubSubTypes.h"

namespace climbsim {
namespace {

using Ids = std::vector<ParticipantId>;

Ids sortedIds(Ids ids) {
  std::sort(ids.begin(), ids.end());
  return ids;
}

/// Waits (on the notifier the endpoints wake) until `ids()` is `want`; returns what it was
/// last (one id of zeros if it was not known).
template <class IdsFn>
Ids waitForIds(Notifier& notifier, IdsFn ids, const Ids& want) {
  const auto deadline = Notifier::Clock::now() + std::chrono::seconds(20);
  while (true) {
    const auto seen = notifier.generation();
    const auto known = ids();
    const Ids now = known ? sortedIds(*known) : Ids{ParticipantId()};
    if (now == sortedIds(want) || !notifier.waitChanged(seen, deadline)) return now;
  }
}

/// The handle of an endpoint of the DDS participant whose prefix starts with `participant`.
MatchedEndpoints::Handle endpointOf(unsigned char participant, unsigned char entity) {
  eprosima::fastrtps::rtps::GUID_t guid;
  guid.guidPrefix.value[0] = participant;
  guid.entityId.value[3] = entity;
  return MatchedEndpoints::Handle(guid);
}

ParticipantId participantOf(unsigned char participant) {
  ParticipantId id;
  id.value[0] = participant;
  return id;
}

TEST(DdsMatching, MatchedEndpointsFollowTheCallbacksAndSayWhenTheyNoLongerKnow) {
  MatchedEndpoints m;
  EXPECT_EQ(m.participants(), Ids{});
  m.update(1, 1, endpointOf(7, 1));
  m.update(2, 1, endpointOf(9, 1));
  m.update(3, 1, endpointOf(9, 2));  // two endpoints of one participant
  EXPECT_EQ(m.count(), 3);
  EXPECT_EQ(sortedIds(*m.participants()), sortedIds({participantOf(7), participantOf(9), participantOf(9)}));
  m.update(2, -1, endpointOf(7, 1));
  EXPECT_EQ(sortedIds(*m.participants()), sortedIds({participantOf(9), participantOf(9)}));

  MatchedEndpoints folded;  // two matches told in one callback: one handle is missing
  folded.update(2, 2, endpointOf(7, 1));
  EXPECT_EQ(folded.count(), 2);
  EXPECT_FALSE(folded.participants().has_value());
  folded.update(3, 1, endpointOf(9, 1));
  EXPECT_FALSE(folded.participants().has_value()) << "which one was lost is still not known";

  MatchedEndpoints read_elsewhere;  // the status read by someone else: a callback without its change
  read_elsewhere.update(1, 0, endpointOf(7, 1));
  EXPECT_EQ(read_elsewhere.count(), 1);
  EXPECT_FALSE(read_elsewhere.participants().has_value());
}

TEST(DdsMatching, ReadersAndWritersNameTheParticipantsOfTheEndpointsTheyMatchedAndForgetThoseThatLeft) {
  const DomainLease domain(100, 199);
  DdsSettings settings;
  settings.domain_id = domain.id();
  settings.resolve();
  DdsContext consumer(settings, "consumer");
  DdsContext producer(settings, "producer");
  auto outsider = std::make_unique<DdsContext>(settings, "outsider");
  Notifier notifier;
  Reader<TestSamplePubSubType> input(consumer, "test/x", "climbsim.step_data", notifier);
  Writer<TestSamplePubSubType> output(consumer, "test/y", "climbsim.step_data", notifier);
  Writer<TestSamplePubSubType> produced(producer, "test/x", "climbsim.step_data", notifier);
  auto forged = std::make_unique<Writer<TestSamplePubSubType>>(*outsider, "test/x", "climbsim.step_data", notifier);
  Reader<TestSamplePubSubType> eavesdropper(*outsider, "test/y", "climbsim.step_data", notifier);

  EXPECT_EQ(waitForIds(notifier, [&] { return input.matchedParticipants(); }, {producer.id(), outsider->id()}),
            sortedIds({producer.id(), outsider->id()}));
  EXPECT_EQ(input.matchedWriters(), 2);
  EXPECT_EQ(waitForIds(notifier, [&] { return output.matchedParticipants(); }, {outsider->id()}), Ids{outsider->id()})
      << "the consumer's writer matched only the outsider's reader";
  EXPECT_EQ(waitForIds(notifier, [&] { return produced.matchedParticipants(); }, {consumer.id()}), Ids{consumer.id()});

  forged.reset();  // the outsider's writer goes: the producer's stays
  EXPECT_EQ(waitForIds(notifier, [&] { return input.matchedParticipants(); }, {producer.id()}), Ids{producer.id()});
}

}  // namespace
}  // namespace climbsim
