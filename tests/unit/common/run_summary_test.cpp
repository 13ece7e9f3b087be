// summary.json (climbsim/run_summary/): the summary of a run from the trace's statistics and how
// it ended; the one the launcher writes when the recorder wrote none (killed, crashed), computed
// from the rows trace.csv kept, outcome and exit code agreeing with the launcher's; and what the
// services' lines add to it.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "climbsim/errors.hpp"
#include "climbsim/run_summary/run_summary.hpp"
#include "climbsim/run_summary/summary_additions.hpp"
#include "climbsim/run_summary/summary_from_trace.hpp"

namespace climbsim::run_summary {
namespace {

namespace fs = std::filesystem;

class FallbackSummary : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("climbsim-run-summary-" + std::to_string(::getpid()));
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
  const auto j = summaryFromTrace(dir_.string(), "crack-descent", kExitFailed, FailedProcess{"recorder", 137});
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
  const auto j = summaryFromTrace(dir_.string(), "crack-descent", kExitFailed, FailedProcess{"recorder", 137});
  EXPECT_DOUBLE_EQ(j["downforce_from_s"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(j["min_downforce_n"].get<double>(), 1000.0) << "the row at 0.01 s only";
  EXPECT_DOUBLE_EQ(j["mean_downforce_n"].get<double>(), 1000.0);
}

TEST_F(FallbackSummary, OutcomeFollowsTheLaunchersExitCode) {
  EXPECT_EQ(summaryFromTrace(dir_.string(), "s", kExitFell, std::nullopt)["outcome"], "fell");
  EXPECT_EQ(summaryFromTrace(dir_.string(), "s", kExitFell, std::nullopt)["fell"], true);
  EXPECT_EQ(summaryFromTrace(dir_.string(), "s", kExitStopped, std::nullopt)["outcome"], "stopped");
  const auto ok = summaryFromTrace(dir_.string(), "s", kExitOk, std::nullopt);
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


TEST(RunSummary, TheTraceStatisticsWithHowTheRunEnded) {
  const nlohmann::json trace = {{"steps", 400}, {"sim_s", 2.0}, {"fell", false}, {"fell_at_s", nullptr}};
  const auto completed = runSummary(trace, "crack-descent", 4.0, RunEnd{"completed", "end of run", "", 0});
  EXPECT_EQ(completed["scenario"], "crack-descent");
  EXPECT_EQ(completed["steps"], 400);
  EXPECT_EQ(completed["completed"], true);
  EXPECT_EQ(completed["fell"], false);
  EXPECT_DOUBLE_EQ(completed["realtime_factor"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(runSummary(trace, "s", 0.0, RunEnd{"completed", "", "", 0})["realtime_factor"].get<double>(), 0.0);
  // A fall no row held: the time from the reason.
  const auto fell = runSummary(trace, "s", 4.0, RunEnd{"fell", "FELL at t = 2.1 s: the robot left", "drive", kExitFell});
  EXPECT_EQ(fell["fell"], true);
  EXPECT_EQ(fell["adhesion_failed"], true);
  EXPECT_EQ(fell["culprit"], "drive");
  EXPECT_EQ(fell["exit_code"], kExitFell);
  EXPECT_DOUBLE_EQ(fell["fell_at_s"].get<double>(), 2.1);
  EXPECT_EQ(fellAtInReason("FELL at t = soon"), std::nullopt);
  EXPECT_STREQ(outcomeOfExitCode(kExitStopped), "stopped");
  EXPECT_STREQ(outcomeOfExitCode(kExitConfig), "failed");
}

TEST_F(FallbackSummary, WrittenAsTheOneWriterWritesIt) {
  const nlohmann::json summary = {{"outcome", "completed"}, {"steps", 3}};
  EXPECT_FALSE(hasSummary(dir_.string()));
  ASSERT_TRUE(writeSummary(dir_.string(), summary));
  EXPECT_TRUE(hasSummary(dir_.string()));
  std::ifstream in(summaryPath(dir_.string()));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, summary.dump(2) + "\n");
  EXPECT_FALSE(writeSummary((dir_ / "no-such-dir").string(), summary));
  EXPECT_FALSE(editSummary((dir_ / "no-such-dir").string(), [](nlohmann::json&) { return true; }));
}

TEST(WheelsOverNothing, TheEntryNamesEachWheelOnceWithTheFirstTime) {
  EXPECT_TRUE(wheelsOverNothingJson({}).is_null());
  const auto j = wheelsOverNothingJson({{1, 2.5}, {3, 2.25}, {1, 3.0}});
  EXPECT_DOUBLE_EQ(j["first_at_s"].get<double>(), 2.25);
  EXPECT_EQ(j["wheels"], nlohmann::json::array({1, 3}));
}

TEST(RunSummary, ASlideBeyondTheLimitOfARunThatStayedOnTheWallIsNamed) {
  const nlohmann::json slid = {{"slid", true}, {"fell", false}, {"slide_m", 0.26444}, {"slide_limit_m", 0.005}};
  EXPECT_EQ(slideBeyondLimit(slid), "the robot slid 264 mm, beyond the scenario's slide_limit_m of 5 mm (adhesion failed)");
  nlohmann::json fell = slid;
  fell["fell"] = true;
  EXPECT_EQ(slideBeyondLimit(fell), "") << "a fall says more than its slide";
  nlohmann::json within = slid;
  within["slid"] = false;
  EXPECT_EQ(slideBeyondLimit(within), "");
  EXPECT_EQ(slideBeyondLimit(nlohmann::json::array()), "");
}

TEST_F(FallbackSummary, ASlideBeyondTheLimitIsReadFromTheRunDirectory) {
  EXPECT_EQ(slideBeyondLimitOf(dir_.string()), "") << "no summary.json";
  ASSERT_TRUE(writeSummary(dir_.string(), {{"slid", true}, {"slide_m", 0.0123}, {"slide_limit_m", 0.01}}));
  EXPECT_EQ(slideBeyondLimitOf(dir_.string()),
            "the robot slid 12.3 mm, beyond the scenario's slide_limit_m of 10 mm (adhesion failed)");
}

}  // namespace
}  // namespace climbsim::run_summary
