// summary.json written by the launcher when the recorder wrote none (killed, crashed): computed
// from the rows trace.csv kept, outcome and exit code agreeing with the launcher's.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "climbsim/errors.hpp"
#include "fallback_summary.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

class FallbackSummary : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("climbsim-fallback-summary-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Three full rows and one cut off mid-row when the recorder was killed.
    std::ofstream(dir_ / "trace.csv") << "t_s,downforce_n,pf_x_m\n"
                                      << "0.000000000,nan,nan\n"
                                      << "0.005000000,1200,0\n"
                                      << "0.010000000,1000,0\n"
                                      << "0.015000000,900";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FallbackSummary, ComputedFromTheKeptRowsNamingTheCulprit) {
  const auto j = fallbackSummary(dir_.string(), "crack-descent", kExitFailed, FailedProcess{"recorder", 137});
  EXPECT_EQ(j["outcome"], "failed");
  EXPECT_EQ(j["exit_code"], kExitFailed);
  EXPECT_EQ(j["completed"], false);
  EXPECT_EQ(j["culprit"], "recorder");
  EXPECT_NE(j["reason"].get<std::string>().find("service 'recorder' exited with code 137"), std::string::npos);
  EXPECT_EQ(j["steps"], 3);
  EXPECT_DOUBLE_EQ(j["sim_s"].get<double>(), 0.010);
  EXPECT_DOUBLE_EQ(j["min_downforce_n"].get<double>(), 1000.0);
  EXPECT_DOUBLE_EQ(j["mean_downforce_n"].get<double>(), 1100.0);
  EXPECT_EQ(j["written_by"], "launcher");
}

TEST_F(FallbackSummary, TheDownforceStatisticsStartAtTheEndOfTheHoldAsTheRecordersDo) {
  std::ofstream(dir_ / "scenario.yaml") << "name: x\nstart: {x_m: 1, y_m: 1, hold_s: 0.01}\n";
  const auto j = fallbackSummary(dir_.string(), "crack-descent", kExitFailed, FailedProcess{"recorder", 137});
  EXPECT_DOUBLE_EQ(j["downforce_from_s"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(j["min_downforce_n"].get<double>(), 1000.0) << "the row at 0.01 s only";
  EXPECT_DOUBLE_EQ(j["mean_downforce_n"].get<double>(), 1000.0);
}

TEST_F(FallbackSummary, OutcomeFollowsTheLaunchersExitCode) {
  EXPECT_EQ(fallbackSummary(dir_.string(), "s", kExitFell, std::nullopt)["outcome"], "fell");
  EXPECT_EQ(fallbackSummary(dir_.string(), "s", kExitFell, std::nullopt)["fell"], true);
  EXPECT_EQ(fallbackSummary(dir_.string(), "s", kExitStopped, std::nullopt)["outcome"], "stopped");
  const auto ok = fallbackSummary(dir_.string(), "s", kExitOk, std::nullopt);
  EXPECT_EQ(ok["outcome"], "completed");
  EXPECT_EQ(ok["completed"], true);
}

TEST_F(FallbackSummary, WrittenOnlyWhereTheRecorderWroteNone) {
  EXPECT_TRUE(ensureSummary(dir_.string(), "s", kExitFailed, FailedProcess{"recorder", 137}));
  std::ifstream in(dir_ / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in)["written_by"], "launcher");
  // The recorder's own summary is never replaced.
  std::ofstream(dir_ / "summary.json", std::ios::trunc) << R"({"outcome": "completed", "steps": 4000})";
  EXPECT_FALSE(ensureSummary(dir_.string(), "s", kExitFailed, std::nullopt));
  std::ifstream again(dir_ / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(again)["steps"], 4000);
  // No trace at all (the run ended before its first step): still a summary, with 0 steps.
  fs::remove(dir_ / "trace.csv");
  fs::remove(dir_ / "summary.json");
  EXPECT_TRUE(ensureSummary(dir_.string(), "s", 3, std::nullopt));
  std::ifstream third(dir_ / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(third)["steps"], 0);
}

TEST(DroppedSamples, TheTokenOfAServiceLineIsRead) {
  EXPECT_EQ(droppedSamplesIn("thermo     | 21:46:27.241 thermo warn: dropped_samples=165 (leakage 0, valve commands 165)"),
            165u);
  EXPECT_EQ(droppedSamplesIn("dropped_samples=0 (thermo samples)"), 0u);
  EXPECT_FALSE(droppedSamplesIn("thermo: dropped samples: leakage 0"));
  EXPECT_FALSE(droppedSamplesIn("dropped_samples=x"));
}

TEST_F(FallbackSummary, DroppedSamplesOfEveryServiceAreSummed) {
  std::ofstream(dir_ / "summary.json", std::ios::trunc) << R"({"outcome": "completed", "dropped_samples": 2})";
  addDroppedSamples(dir_.string(), {{"thermo", 165}, {"drive", 0}, {"sealing-0", 3}});
  std::ifstream in(dir_ / "summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["dropped_samples"], 170);
  EXPECT_EQ(j["dropped_samples_by_service"]["recorder"], 2);
  EXPECT_EQ(j["dropped_samples_by_service"]["thermo"], 165);
  EXPECT_EQ(j["dropped_samples_by_service"]["sealing-0"], 3);
  EXPECT_EQ(j["outcome"], "completed");
  // Done twice (it never is, but): the recorder's own count is kept, not summed again.
  addDroppedSamples(dir_.string(), {{"thermo", 165}});
  std::ifstream again(dir_ / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(again)["dropped_samples"], 167);
}

TEST(WheelsOverNothing, TheDrivesLineIsRead) {
  const auto w = wheelOverNothingIn(
      "drive      | 04:12:01.120 drive warn: drive: wheel 2 stands over nothing at t = 3.215 s: no wall within 0.050 m");
  ASSERT_TRUE(w);
  EXPECT_EQ(w->wheel, 2);
  EXPECT_DOUBLE_EQ(w->at_s, 3.215);
  EXPECT_FALSE(wheelOverNothingIn("sealing: at t = 0.020 s segment 'outer2' hangs over nothing: 44 %"));
  EXPECT_FALSE(wheelOverNothingIn("wheel x stands over nothing at t = 1 s"));
  EXPECT_FALSE(wheelOverNothingIn("wheel 2 stands over nothing at t = later"));
}

TEST_F(FallbackSummary, WheelsOverNothingAreMarkedWithTheFirstTimeOrNull) {
  std::ofstream(dir_ / "summary.json", std::ios::trunc) << R"({"outcome": "completed"})";
  addWheelsOverNothing(dir_.string(), {});
  {
    std::ifstream in(dir_ / "summary.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_TRUE(j.contains("wheels_over_nothing"));
    EXPECT_TRUE(j["wheels_over_nothing"].is_null());
  }
  addWheelsOverNothing(dir_.string(), {{3, 4.5}, {2, 4.25}});
  std::ifstream in(dir_ / "summary.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(j["wheels_over_nothing"]["first_at_s"].get<double>(), 4.25);
  EXPECT_EQ(j["wheels_over_nothing"]["wheels"], nlohmann::json::array({3, 2}));
  EXPECT_EQ(j["outcome"], "completed");
}

TEST_F(FallbackSummary, AnEmptyReasonOfAFailedRunIsTheClocksAndNamesItsCulprit) {
  std::ofstream(dir_ / "summary.json", std::ios::trunc) << R"({"outcome": "failed", "reason": "", "culprit": ""})";
  const std::string clock = "participant 'controller' vanished (DDS dropped it) before step 0";
  EXPECT_TRUE(fillFailureReason(dir_.string(), clock));
  {
    std::ifstream in(dir_ / "summary.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j["reason"], clock);
    EXPECT_EQ(j["culprit"], "controller");
  }
  EXPECT_FALSE(fillFailureReason(dir_.string(), "another")) << "a reason is kept";
  std::ofstream(dir_ / "summary.json", std::ios::trunc) << R"({"outcome": "completed", "reason": ""})";
  EXPECT_FALSE(fillFailureReason(dir_.string(), clock)) << "only a failed run";
}

}  // namespace
}  // namespace climbsim::launcher
