// When the sealing service publishes the pictures a run keeps: the first due step at or after
// each requested time that has pictures, once per step.

#include <gtest/gtest.h>

#include "picture_schedule.hpp"

namespace climbsim::sealing {
namespace {

TEST(PictureSchedule, DueAtTheFirstStepAtOrAfterEachRequestedTime) {
  PictureSchedule s({0.1, 0.02, 0.021});  // any order
  EXPECT_FALSE(s.empty());
  EXPECT_FALSE(s.due(15'000'000));
  EXPECT_TRUE(s.due(20'000'000));  // exactly at 0.02 s
  // Not served (no pictures yet at that step): still due at the next step.
  EXPECT_TRUE(s.due(40'000'000));
  s.served(40'000'000);  // serves 0.02 and 0.021 at once
  EXPECT_EQ(s.pending(), 1u);
  EXPECT_FALSE(s.due(60'000'000));
  EXPECT_TRUE(s.due(100'000'000));
  s.served(100'000'000);
  EXPECT_EQ(s.pending(), 0u);
  EXPECT_FALSE(s.due(1'000'000'000));
}

TEST(PictureSchedule, NothingRequestedIsNeverDue) {
  PictureSchedule s({});
  EXPECT_TRUE(s.empty());
  EXPECT_FALSE(s.due(0));
}

}  // namespace
}  // namespace climbsim::sealing
