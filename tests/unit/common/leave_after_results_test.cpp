// An abort once a process's results are complete ends it with the run's exit code and a line
// naming it, and so do a leave that lasts past its deadline (a deadlock in Fast DDS's
// teardown) and a SIGTERM during the leave; an abort or a SIGTERM before that stays a crash.
// A process whose results are complete ends with its output written but without static
// destructors.

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "climbsim/leave_after_results.hpp"
#include "climbsim/main_guard.hpp"

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

TEST(LeaveAfterResults, ASigtermDuringTheLeaveExitsWithTheRunsCodeAndSaysWhy) {
  EXPECT_EXIT(
      {
        climbsim::leaveAfterResults("drive", 0);
        ::raise(SIGTERM);  // as the launcher's grace after the clock ended
        for (;;) ::pause();
      },
      ::testing::ExitedWithCode(0),
      "drive: asked to end \\(SIGTERM\\) while its participant left DDS after the run; .*\\(exit code 0\\)");
}

TEST(LeaveAfterResults, ASigtermBeforeTheResultsAreCompleteStillTerminates) {
  EXPECT_EXIT(::raise(SIGTERM), ::testing::KilledBySignal(SIGTERM), "");
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

namespace {

/// A static object whose destructor says it ran (as Fast DDS's participant factory sleeps in its).
struct SaysWhenDestroyed {
  ~SaysWhenDestroyed() { std::fputs("static teardown ran\n", stderr); }
};

int guardedMainOf(const std::function<int()>& body) {
  CLI::App app("test");
  char name[] = "test";
  char* argv[] = {name, nullptr};
  return climbsim::guardedMain(app, 1, argv, "test", body);
}

TEST(LeaveAfterResults, AProcessWhoseResultsAreCompleteEndsWithItsCodeAndItsOutputWrittenButNoStaticTeardown) {
  // A fresh process, not a fork: a fork of a process with Fast DDS threads hangs in its teardown.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        static SaysWhenDestroyed destroyed;
        std::exit(guardedMainOf([] {
          climbsim::leaveAfterResults("recorder", 4);
          std::fputs("unflushed C output, ", stderr);
          std::cerr << "a stream's output" << std::flush;
          spdlog::error("and the last log line");
          return 4;
        }));
      },
      ::testing::ExitedWithCode(4), "unflushed C output, a stream's output.*and the last log line\n$");
}

TEST(LeaveAfterResults, AProcessWithoutCompleteResultsEndsWithItsStaticTeardown) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        static SaysWhenDestroyed destroyed;
        std::exit(guardedMainOf([] { return 3; }));
      },
      ::testing::ExitedWithCode(3), "static teardown ran\n$");
}

}  // namespace
