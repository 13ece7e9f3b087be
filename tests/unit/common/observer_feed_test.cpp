// ObserverFeed: the observers' thinned copy of the record batches.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "climbsim/observer_feed.hpp"

using namespace std::chrono_literals;
using climbsim::ObserverFeed;
using climbsim::RecordBatch;
using climbsim::RecordedSample;

namespace {

RecordedSample sample(const std::string& topic, std::uint64_t step, unsigned char byte) {
  RecordedSample s;
  s.topic(topic);
  s.step(step);
  s.cdr().assign(1, byte);
  return s;
}

RecordBatch batch(std::initializer_list<RecordedSample> samples) {
  RecordBatch b;
  for (const auto& s : samples) b.samples().push_back(s);
  return b;
}

}  // namespace

TEST(ObserverFeed, KeepsTheNewestSampleOfEachTopicAcrossBatchesInStepOrder) {
  ObserverFeed feed(33ms);
  const auto t0 = ObserverFeed::Clock::time_point{} + 10s;
  feed.add(batch({sample("thermo/ChamberState", 8, 1), sample("thermo/AdhesionForce", 8, 2),
                  sample("thermo/ChamberState", 9, 3)}));
  feed.add(batch({sample("thermo/ChamberState", 10, 4), sample("scene/DepthGrid", 4, 5)}));
  ASSERT_TRUE(feed.due(t0));
  const auto out = feed.take(t0, "thermo", 7, 11);
  EXPECT_EQ(out.source().to_string(), "thermo");
  EXPECT_EQ(out.run_id(), 7u);
  EXPECT_EQ(out.end_step(), 11u);
  ASSERT_EQ(out.samples().size(), 3u) << "one per topic";
  EXPECT_EQ(out.samples()[0].topic().to_string(), "scene/DepthGrid");
  EXPECT_EQ(out.samples()[1].topic().to_string(), "thermo/AdhesionForce");
  EXPECT_EQ(out.samples()[2].topic().to_string(), "thermo/ChamberState");
  EXPECT_EQ(out.samples()[2].step(), 10u) << "the newest";
  EXPECT_EQ(out.samples()[2].cdr().at(0), 4);
  EXPECT_EQ(out.first_step(), 4u);
  EXPECT_FALSE(feed.pending()) << "taken";
}

TEST(ObserverFeed, SendsAtMostOncePerPeriodAndNothingWhenNothingWaits) {
  ObserverFeed feed(33ms);
  auto t = ObserverFeed::Clock::time_point{} + 10s;
  EXPECT_FALSE(feed.due(t)) << "nothing waits";
  feed.add(batch({sample("drive/RobotState", 1, 1)}));
  ASSERT_TRUE(feed.due(t));
  feed.take(t, "drive", 1, 2);
  feed.add(batch({sample("drive/RobotState", 2, 2)}));
  EXPECT_FALSE(feed.due(t + 20ms)) << "within the period";
  EXPECT_TRUE(feed.pending()) << "but it waits (sent at once when the run ends)";
  EXPECT_TRUE(feed.due(t + 33ms));
  // An older sample never replaces a newer one of the same topic.
  feed.add(batch({sample("drive/RobotState", 1, 9)}));
  const auto out = feed.take(t + 40ms, "drive", 1, 3);
  ASSERT_EQ(out.samples().size(), 1u);
  EXPECT_EQ(out.samples()[0].step(), 2u);
}
