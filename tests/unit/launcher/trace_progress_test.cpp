#include "trace_progress.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace climbsim::launcher {
namespace {

class TraceTailTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("climbsim-trace-tail-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "trace.csv").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void append(const std::string& text) { std::ofstream(path_, std::ios::app) << text; }

  std::filesystem::path dir_;
  std::string path_;
};

TEST_F(TraceTailTest, NoFileNoRow) {
  TraceTail tail(path_);
  EXPECT_FALSE(tail.poll().has_value());
}

TEST_F(TraceTailTest, FollowsCompleteRowsOnly) {
  TraceTail tail(path_);
  append("t_s,downforce_n,x_m\n0.005,100,1\n");
  auto sample = tail.poll();
  ASSERT_TRUE(sample.has_value());
  EXPECT_DOUBLE_EQ(sample->t_s, 0.005);
  EXPECT_DOUBLE_EQ(sample->downforce_n.value(), 100.0);
  EXPECT_EQ(sample->rows, 1u);
  append("0.01,150,1\n0.015,2");  // the last row is half written
  sample = tail.poll();
  EXPECT_DOUBLE_EQ(sample->t_s, 0.01);
  EXPECT_EQ(sample->rows, 2u);
  append("00,1\n");
  sample = tail.poll();
  EXPECT_DOUBLE_EQ(sample->t_s, 0.015);
  EXPECT_DOUBLE_EQ(sample->downforce_n.value(), 200.0);
  EXPECT_EQ(sample->rows, 3u);
}

TEST_F(TraceTailTest, SkipsMalformedRowsAndStartsOverOnANewFile) {
  TraceTail tail(path_);
  append("t_s,downforce_n\n1,10\nnot,a number\n");
  EXPECT_DOUBLE_EQ(tail.poll()->t_s, 1.0);
  std::ofstream(path_, std::ios::trunc) << "t_s,downforce_n\n";
  EXPECT_FALSE(tail.poll().has_value());
  append("0.5,7\n");
  EXPECT_DOUBLE_EQ(tail.poll()->t_s, 0.5);
}

TEST(ProgressText, ShowsTimeShareSpeedForceAndState) {
  TraceSample sample;
  sample.t_s = 5.0;
  sample.downforce_n = 2186.4;
  EXPECT_EQ(progressText(sample, 20.0, 3.42, "running"), "t 5.00/20 s (25%)  3.4x real time  F 2186 N  running");
  EXPECT_EQ(progressText(std::nullopt, 20.0, std::nullopt, "starting"), "t -  starting");
  sample.downforce_n.reset();
  EXPECT_EQ(progressText(sample, 0.0, std::nullopt, "stopping"), "t 5.00 s  stopping");
}

}  // namespace
}  // namespace climbsim::launcher

namespace climbsim::launcher {
namespace {

TEST(RateMeter, TheRateOfAnEndedRunIsUpToItsLastRowNotUpToNow) {
  RateMeter meter;
  EXPECT_FALSE(meter.rate(0.0, false)) << "no row yet";
  meter.see(0.0, 0.0);
  EXPECT_FALSE(meter.rate(0.1, false)) << "too short to tell";
  meter.see(1.0, 5.0);
  meter.see(2.0, 10.0);
  EXPECT_DOUBLE_EQ(*meter.rate(2.0, false), 5.0);
  // The run is paused: no new row, the live rate falls.
  meter.see(4.0, 10.0);
  EXPECT_DOUBLE_EQ(*meter.rate(4.0, false), 2.5);
  // It ended at its last row (2 s); the launcher waits 30 s more for the viewer: still 5x.
  EXPECT_DOUBLE_EQ(*meter.rate(34.0, true), 5.0);
  // A run whose only row came at the end has no rate to tell (not 0.0x).
  RateMeter late;
  late.see(0.0, 20.0);
  late.see(3.0, 20.0);
  EXPECT_FALSE(late.rate(3.0, true));
}

}  // namespace
}  // namespace climbsim::launcher
