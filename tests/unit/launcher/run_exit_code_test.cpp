// The run's exit code from its processes' codes: bad input (a process exiting 2) is exit 2
// wherever it was found, and summary.json is made to agree.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "climbsim/errors.hpp"
#include "run_exit_code.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

TEST(RunExitCode, AServiceRefusingItsConfigurationMakesTheRunExitTwoThoughTheClockSaysFailed) {
  // A shard reading from a producer not on the roster: it exits 2, the clock 1, the others 1.
  const std::vector<ProcessEnd> ends = {
      {"clock", kExitFailed}, {"scene-0", kExitFailed}, {"sealing-0", kExitConfig}, {"recorder", kExitFailed}};
  EXPECT_EQ(runExitCode(ends), kExitConfig);
  EXPECT_EQ(configCulprit(ends), std::optional<std::string>("sealing-0"));
}

TEST(RunExitCode, ServicesFoundEndedTogetherAreBlamedKilledOnesFirstThenInTheirOrder) {
  // The recorder killed (137): the clock tells thermo and drive, which exit 1, before the
  // launcher looks; thermo is listed before the recorder but must not be named for it.
  EXPECT_EQ(blameOrder({kExitFailed, 128 + 9, kExitFailed}), (std::vector<std::size_t>{1, 0, 2}));
  // One killed, one crashed (SIGSEGV): the signals first, in the composition's order.
  EXPECT_EQ(blameOrder({kExitFailed, 128 + 9, kExitConfig, 128 + 11}), (std::vector<std::size_t>{1, 3, 0, 2}));
  // No signal: the composition's order, as before.
  EXPECT_EQ(blameOrder({kExitFailed, kExitConfig, kExitOk}), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(blameOrder({}).empty());
}

TEST(RunExitCode, ASecuredStartGivenUpForAStalledHandshakeIsMadeAgainUpToItsLastStart) {
  // Two participants whose handshake stalled give the start up (75); the clock and the
  // others only saw a participant fail.
  const std::vector<ProcessEnd> stalled = {{"clock", kExitFailed},
                                           {"controller", kExitRetryStart},
                                           {"thermo", kExitRetryStart},
                                           {"drive", kExitFailed}};
  EXPECT_TRUE(startAgain(stalled, true, 1));
  EXPECT_TRUE(startAgain(stalled, true, kMaxStarts - 1));
  EXPECT_FALSE(startAgain(stalled, true, kMaxStarts)) << "kMaxStarts starts in all";
  EXPECT_FALSE(startAgain(stalled, false, 1)) << "an unsecured run has no handshake to stall";
  // The clock itself gave the start up (its own handshake with the recorder stalled): the run
  // says so with 75, and is started again.
  const std::vector<ProcessEnd> clock_stalled = {{"clock", kExitRetryStart},
                                                 {"recorder", kExitRetryStart},
                                                 {"drive", kExitFailed}};
  EXPECT_EQ(runExitCode(clock_stalled), kExitRetryStart);
  EXPECT_TRUE(startAgain(clock_stalled, true, 1));
  // A run that failed, was stopped or refused its configuration is not started again.
  EXPECT_FALSE(startAgain({{"clock", kExitFailed}, {"drive", kExitFailed}}, true, 1));
  EXPECT_FALSE(startAgain({{"clock", kExitStopped}, {"drive", kExitOk}}, true, 1));
  EXPECT_FALSE(startAgain({{"clock", kExitFailed}, {"sealing", kExitConfig}}, true, 1));
  EXPECT_FALSE(startAgain({{"clock", kExitOk}, {"drive", std::nullopt}}, true, 1));
}

TEST(RunExitCode, WithoutAConfigurationErrorTheClockDecides) {
  EXPECT_EQ(runExitCode({{"clock", kExitOk}, {"drive", kExitOk}}), kExitOk);
  EXPECT_EQ(runExitCode({{"clock", kExitFell}, {"drive", kExitOk}}), kExitFell);
  EXPECT_EQ(runExitCode({{"clock", kExitStopped}, {"drive", kExitFailed}}), kExitStopped);
  EXPECT_EQ(runExitCode({{"clock", kExitOk}, {"drive", 137}}), kExitFailed);
  EXPECT_EQ(runExitCode({{"clock", kExitOk}, {"drive", std::nullopt}}), kExitFailed);
  EXPECT_EQ(runExitCode({{"clock", kExitConfig}, {"drive", kExitFailed}}), kExitConfig);
  EXPECT_EQ(configCulprit({{"clock", kExitConfig}, {"drive", kExitFailed}}), std::nullopt);
  EXPECT_EQ(runExitCode({}), kExitFailed);
}

class AgreeOnConfigError : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("climbsim-run-exit-code-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  nlohmann::json summary() const {
    std::ifstream in(dir_ / "summary.json");
    return nlohmann::json::parse(in);
  }
  fs::path dir_;
};

TEST_F(AgreeOnConfigError, TheRecordersFailedSummaryTakesExitCodeTwoAndKeepsTheReason) {
  const std::string reason = "'sealing-0' reads topic 'scene/DepthImage' from 'scene-70', which is not a producer";
  std::ofstream(dir_ / "summary.json") << nlohmann::json{{"outcome", "failed"}, {"exit_code", 1}, {"completed", false},
                                                         {"reason", reason}, {"culprit", "sealing-0"}, {"steps", 0}}
                                              .dump();
  EXPECT_TRUE(agreeOnConfigError(dir_.string(), kExitConfig, "sealing-0"));
  const auto j = summary();
  EXPECT_EQ(j["exit_code"], kExitConfig);
  EXPECT_EQ(j["outcome"], "failed");
  EXPECT_EQ(j["completed"], false);
  EXPECT_EQ(j["reason"], reason);
  EXPECT_EQ(j["culprit"], "sealing-0");
  EXPECT_EQ(j["configuration_error"], true);
  EXPECT_FALSE(agreeOnConfigError(dir_.string(), kExitConfig, "sealing-0")) << "already agrees";
}

TEST_F(AgreeOnConfigError, NamesTheCulpritWhenTheSummaryHasNoneAndLeavesOtherCodesAlone) {
  std::ofstream(dir_ / "summary.json") << nlohmann::json{{"outcome", "failed"}, {"exit_code", 1}, {"culprit", ""}}.dump();
  EXPECT_FALSE(agreeOnConfigError(dir_.string(), kExitFailed, "x"));
  EXPECT_EQ(summary()["exit_code"], 1);
  EXPECT_TRUE(agreeOnConfigError(dir_.string(), kExitConfig, "drive"));
  EXPECT_EQ(summary()["culprit"], "drive");
  fs::remove(dir_ / "summary.json");
  EXPECT_FALSE(agreeOnConfigError(dir_.string(), kExitConfig, "drive")) << "no summary: nothing to agree with";
}

}  // namespace
}  // namespace climbsim::launcher
