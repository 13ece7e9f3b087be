// An abort once a process's results are complete ends it with the run's exit code and a line
// naming it; an abort before that stays a crash (SIGABRT).

#include <gtest/gtest.h>

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
