#include "climbsim/schedule.hpp"

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"

namespace climbsim {
namespace {

TEST(Schedule, DueStepsFollowPeriodAndOffset) {
  const Schedule s{4, 1};
  std::vector<std::uint64_t> due;
  for (std::uint64_t k = 0; k < 14; ++k) {
    if (s.isDue(k)) due.push_back(k);
  }
  EXPECT_EQ(due, (std::vector<std::uint64_t>{1, 5, 9, 13}));
}

TEST(Schedule, PeriodOneIsDueEveryStep) {
  const Schedule s{1, 0};
  for (std::uint64_t k = 0; k < 100; ++k) EXPECT_TRUE(s.isDue(k));
}

TEST(Schedule, LastDueBeforeIsTheZeroOrderHoldStamp) {
  const Schedule s{3, 2};
  EXPECT_FALSE(s.lastDueBefore(0));
  EXPECT_FALSE(s.lastDueBefore(2));  // due at 2 itself: a consumer at 2 reads earlier stamps only
  EXPECT_EQ(s.lastDueBefore(3), 2u);
  EXPECT_EQ(s.lastDueBefore(5), 2u);
  EXPECT_EQ(s.lastDueBefore(6), 5u);
}

TEST(Schedule, LastDueBeforeAgreesWithBruteForce) {
  for (std::uint32_t period = 1; period <= 7; ++period) {
    for (std::uint32_t offset = 0; offset < period; ++offset) {
      const Schedule s{period, offset};
      std::optional<std::uint64_t> last;
      std::uint64_t count = 0;
      for (std::uint64_t k = 0; k < 60; ++k) {
        EXPECT_EQ(s.lastDueBefore(k), last) << period << "/" << offset << " at " << k;
        EXPECT_EQ(s.dueCount(k), count);
        std::uint64_t next = k;
        while (!s.isDue(next)) ++next;
        EXPECT_EQ(s.nextDueFrom(k), next);
        if (s.isDue(k)) {
          last = k;
          ++count;
        }
      }
    }
  }
}

TEST(Schedule, ValidateRejectsZeroPeriodAndLargeOffset) {
  EXPECT_THROW((Schedule{0, 0}.validate("x")), ConfigError);
  EXPECT_THROW((Schedule{2, 2}.validate("x")), ConfigError);
  EXPECT_NO_THROW((Schedule{2, 1}.validate("x")));
  try {
    Schedule{0, 0}.validate("participant 'sealing'");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("participant 'sealing'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("period_steps = 0"), std::string::npos);
  }
}

}  // namespace
}  // namespace climbsim
