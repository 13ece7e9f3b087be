// What a sweep reports of a finished variant: sweep.csv tells how each run ended as its
// summary.json says it (a slide beyond the limit too), the legends mark slid and fell variants,
// and the progress line counts them.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sweep/sweep_progress.hpp"
#include "sweep/sweep_results.hpp"

namespace {

namespace fs = std::filesystem;
using namespace climbsim::sweep;

class SweepRunEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("climbsim-sweep-results-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "trace.csv") << "t_s,downforce_n,pf_x_m,pf_y_m\n0,0,0,0\n0.5,900,0.03,0.04\n1,700,0,0\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  void summary(const nlohmann::json& j) { std::ofstream(dir_ / "summary.json") << j.dump(2); }
  fs::path dir_;
};

TEST_F(SweepRunEnd, TheRowTellsHowTheRunEndedAsItsSummarySaysIt) {
  summary({{"outcome", "completed"}, {"fell", false}, {"fell_at_s", nullptr}, {"max_slip_mps", 0.76},
           {"slide_m", 0.26}, {"slide_limit_m", 0.005}, {"slid", true}, {"adhesion_failed", true},
           {"seal_over_nothing", {{"first_at_s", 3.5}, {"segments", 2}}}, {"wheels_over_nothing", nullptr},
           {"dropped_samples", 0}, {"exit_code", 0}, {"culprit", ""}, {"reason", "end of run after 4000 steps"}});
  const SweepAxis axis{"controller.downforce_n", {"900"}};
  const Variant v{0, {"900"}, {"controller.downforce_n=900"}, "000_controller.downforce_n=900"};
  const VariantResult r = readVariant(v, dir_.string(), 1.5, 0.5);
  EXPECT_TRUE(r.slid);
  EXPECT_TRUE(r.adhesion_failed);
  EXPECT_DOUBLE_EQ(r.slide_m, 0.26);
  EXPECT_EQ(r.seal_over_nothing_at_s, 3.5);
  EXPECT_FALSE(r.fell_at_s);
  const std::string csv = sweepCsv({axis}, {r});
  // The columns a sweep always had, in their order, then how the run ended.
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "variant,controller.downforce_n,outcome,fell,min_downforce_n,mean_downforce_n,max_pf_shift_m,max_slip_mps,"
            "wall_s,dir,slid,slide_m,slide_limit_m,adhesion_failed,fell_at_s,seal_over_nothing_at_s,"
            "wheels_over_nothing_at_s,dropped_samples,exit_code,culprit,reason");
  EXPECT_NE(csv.find("\n0,900,completed,false,700,800,0.050000000000000003,0.76000000000000001,1.5,"
                     "000_controller.downforce_n=900,true,0.26000000000000001,0.0050000000000000001,true,,3.5,,0,0,,"
                     "end of run after 4000 steps\n"),
            std::string::npos)
      << csv;
  EXPECT_EQ(outcomeMark(r), " (slid)");
}

TEST_F(SweepRunEnd, LegendsMarkFellSlidFailedAndStoppedVariants) {
  VariantResult r;
  r.outcome = "completed";
  EXPECT_EQ(outcomeMark(r), "");
  r.slid = true;
  EXPECT_EQ(outcomeMark(r), " (slid)");
  r.fell = true;
  r.outcome = "fell";
  EXPECT_EQ(outcomeMark(r), " (fell)") << "a fall says more than its slide";
  r.fell = false;
  r.outcome = "failed";
  EXPECT_EQ(outcomeMark(r), " (failed)");
  r.outcome = "stopped";
  EXPECT_EQ(outcomeMark(r), " (stopped)");
}

TEST(SweepProgress, OneLineWithEveryCountAndTheTimeLeft) {
  SweepCounts c;
  c.total = 8;
  c.done = 2;
  c.fell = 1;
  c.slid = 1;
  c.running = 2;
  c.queued = 4;
  EXPECT_EQ(progressLine(c, 10.0),
            "sweep: [#######.......................] 2/8 done (1 fell, 1 slid, 0 failed), 2 running, 4 queued, 10 s, "
            "about 30 s left");
  c.done = 0;
  EXPECT_EQ(progressLine(c, 3.0).find("left"), std::string::npos) << "no estimate before the first is done";
}

}  // namespace
