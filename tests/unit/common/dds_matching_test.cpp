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

/// Waits (on the notifier the endpoints wake) until `ids()` is `want`; returns what it was last.
template <class IdsFn>
Ids waitForIds(Notifier& notifier, IdsFn ids, const Ids& want) {
  const auto deadline = Notifier::Clock::now() + std::chrono::seconds(20);
  while (true) {
    const auto seen = notifier.generation();
    const Ids now = sortedIds(ids());
    if (now == sortedIds(want) || !notifier.waitChanged(seen, deadline)) return now;
  }
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
