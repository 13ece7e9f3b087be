// The in-process topics give the stamps the lockstep gives (docs/design.md#horizons).

#include <gtest/gtest.h>

#include "robot.h"
#include "runner/stamped_bus.hpp"

namespace {

using climbsim::Schedule;
using climbsim::solo::Lag;
using climbsim::solo::StampedTopic;

climbsim::DriveCommand command(double vx) {
  climbsim::DriveCommand c;
  c.vx_mps(vx);
  return c;
}

TEST(StampedTopic, AConsumerReadsTheLastDueStampBeforeItsStepAndHoldsIt) {
  StampedTopic<climbsim::DriveCommand> topic("t");
  topic.addProducer("p", Schedule{4, 1});  // due at 1, 5, 9, ...
  EXPECT_TRUE(topic.get(0, Lag::kOneStep).empty());
  EXPECT_TRUE(topic.get(1, Lag::kOneStep).empty()) << "no same-step data";
  topic.write("p", 1, 5, command(1.0));
  for (std::uint64_t k = 2; k <= 5; ++k) {
    const auto got = topic.get(k, Lag::kOneStep);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].step(), 1u) << "k = " << k;
    EXPECT_EQ(got[0].t_ns(), 5);
    EXPECT_EQ(got[0].source(), "p");
  }
  topic.write("p", 5, 25, command(2.0));
  EXPECT_EQ(topic.get(5, Lag::kOneStep).at(0).vx_mps(), 1.0) << "step 5 still reads stamp 1";
  EXPECT_EQ(topic.get(5, Lag::kSameStep).at(0).vx_mps(), 2.0);
  EXPECT_EQ(topic.get(6, Lag::kOneStep).at(0).vx_mps(), 2.0);
}

TEST(StampedTopic, TheRecorderReadsAProducersInitialStateBeforeItsFirstDueStep) {
  // As RecordedInput::get: the initial state (RecordBatch.initial) until the first stamp;
  // other consumers never see it.
  StampedTopic<climbsim::DriveCommand> topic("t");
  topic.addProducer("late", Schedule{4, 1});   // first due at 1, read from step 2 on
  topic.addProducer("quiet", Schedule{1, 0});  // gives no initial state
  topic.setInitial("late", command(7.0));
  EXPECT_THROW(topic.setInitial("nobody", command(0.0)), std::logic_error);
  for (std::uint64_t k = 0; k <= 1; ++k) {
    if (k == 1) topic.write("quiet", 0, 0, command(3.0));
    const auto got = topic.getRecorded(k);
    ASSERT_EQ(got.size(), k == 0 ? 1u : 2u) << "k = " << k;
    EXPECT_EQ(got[0].source(), "late");
    EXPECT_EQ(got[0].vx_mps(), 7.0);
    EXPECT_EQ(got[0].step(), 0u);
    EXPECT_EQ(got[0].t_ns(), 0);
    EXPECT_EQ(topic.get(k, Lag::kOneStep).size(), k == 0 ? 0u : 1u) << "a lockstep input has no initial state";
  }
  topic.write("quiet", 1, 5, command(3.0));
  topic.write("late", 1, 5, command(8.0));
  EXPECT_EQ(topic.getRecorded(2).at(0).vx_mps(), 8.0) << "from its first stamp on, the stamps";
}

TEST(StampedTopic, SeveralProducersComeInNameOrder) {
  StampedTopic<climbsim::DriveCommand> topic("t");
  topic.addProducer("b", Schedule{1, 0});
  topic.addProducer("a", Schedule{1, 0});
  topic.write("b", 0, 0, command(2.0));
  topic.write("a", 0, 0, command(1.0));
  const auto got = topic.get(1, Lag::kOneStep);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].source(), "a");
  EXPECT_EQ(got[1].source(), "b");
}

TEST(StampedTopic, AMissingStampOrAWriteOffScheduleIsALogicError) {
  StampedTopic<climbsim::DriveCommand> topic("t");
  topic.addProducer("p", Schedule{2, 0});
  EXPECT_THROW(topic.get(1, Lag::kOneStep), std::logic_error) << "stamp 0 was never written";
  EXPECT_THROW(topic.write("p", 1, 0, command(0.0)), std::logic_error) << "not due at 1";
  EXPECT_THROW(topic.write("q", 0, 0, command(0.0)), std::logic_error) << "no producer q";
  topic.write("p", 0, 0, command(0.0));
  EXPECT_THROW(topic.write("p", 0, 0, command(0.0)), std::logic_error) << "twice";
}

}  // namespace
