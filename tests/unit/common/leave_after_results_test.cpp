// An abort once a process's results are complete ends it with the run's exit code and a line
// naming it, and so does a leave that lasts past its deadline (a deadlock in Fast DDS's
// teardown); an abort before that stays a crash (SIGABRT).

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdlib>

#include "climbsim/leave_after_results.hpp"

namespace {

TEST(LeaveAfterResults, AnAbortAfterTheResultsExitsWithTheRunsCodeAndSaysWhy) {
  EXPECT_EXIT(
      {
        climbsim::leaveAfterResults("sealing-0", 0);
        std::abort();
      },
      ::testing::ExitedWithCode(0), "sealing-0: Fast DDS aborted while the participants left after the run");
  EXPECT_EXIT(
      {
        climbsim::leaveAfterResults("drive", 3);
        std::abort();
      },
      ::testing::ExitedWithCode(3), "drive: .*\\(exit code 3\\)");
}

TEST(LeaveAfterResults, ALeaveThatHangsPastItsDeadlineExitsWithTheRunsCodeAndSaysWhy) {
  EXPECT_EXIT(
      {
        climbsim::leaveAfterResults("clock", 5, 1);
        for (;;) ::pause();  // as a teardown that waits for ever
      },
      ::testing::ExitedWithCode(5),
      "clock: Fast DDS did not let the participant leave within 1 s after the run; .*\\(exit code 5\\)");
}

TEST(LeaveAfterResults, AnAbortBeforeTheResultsAreCompleteStaysACrash) {
  EXPECT_EXIT(std::abort(), ::testing::KilledBySignal(SIGABRT), "");
}

TEST(LeaveAfterResults, ALongNameIsCutNotOverrun) {
  const std::string name(300, 'n');
  EXPECT_EXIT(
      {
        climbsim::leaveAfterResults(name.c_str(), 1);
        std::abort();
      },
      ::testing::ExitedWithCode(1), std::string(63, 'n') + ": Fast DDS");
}

}  // namespace
