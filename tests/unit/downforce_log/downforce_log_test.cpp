// The downforce log's model: one line per period of simulated time, at the first sample that
// holds at or after each multiple of the period, stamped with the time the sample holds at.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "downforce_log.hpp"

namespace climbsim::downforce_log {
namespace {

constexpr std::int64_t kDt = 5'000'000;  // 5 ms steps

/// Steps the model through steps [first, last) with F = 2000 + step, set-point 2200 N;
/// returns the times [s] of the lines it gave.
std::vector<double> lineTimes(const DownforceLog& model, DownforceLog::State& state, std::int64_t first,
                              std::int64_t last, std::int64_t stride = 1) {
  std::vector<double> times;
  for (std::int64_t k = first; k < last; k += stride) {
    const auto out = model.step(state, {2000.0 + static_cast<double>(k), 2200.0}, k * kDt, kDt);
    if (out.due) times.push_back(out.t_s);
  }
  return times;
}

TEST(DownforceLog, OneLinePerSecondAtTheSampleHoldingAtEachWholeSecond) {
  const DownforceLog model(DownforceLogParams{});
  auto state = model.initialState();
  // 5 s of 5 ms steps: step k holds at (k + 1) dt, so step 199 holds at 1.000 s.
  EXPECT_EQ(lineTimes(model, state, 0, 1000), (std::vector<double>{1.0, 2.0, 3.0, 4.0, 5.0}));
}

TEST(DownforceLog, TheLineOfStep199SaysItsValuesAndTheTimeTheyHoldAt) {
  const DownforceLog model(DownforceLogParams{});
  auto state = model.initialState();
  const auto before = model.step(state, {2187.44, 2200.0}, 197 * kDt, kDt);
  EXPECT_FALSE(before.due);
  EXPECT_TRUE(before.line.empty());
  const auto out = model.step(state, {2187.44, 2200.0}, 199 * kDt, kDt);
  ASSERT_TRUE(out.due);
  EXPECT_EQ(out.line, "t = 1.000 s: F = 2187.4 N (set-point 2200 N)");
  EXPECT_EQ(state.next_due_ns, 2'000'000'000);
}

TEST(DownforceLog, NoSetPointIsSaidSo) {
  EXPECT_EQ(formatLine(3.0, {1500.25, 0.0}), "t = 3.000 s: F = 1500.2 N (no set-point)");
  EXPECT_EQ(formatLine(0.25, {-12.0, 1800.0}), "t = 0.250 s: F = -12.0 N (set-point 1800 N)");
}

TEST(DownforceLog, MissedSamplesGiveTheNextSampleAndDoNotDelayLaterLines) {
  const DownforceLog model(DownforceLogParams{});
  auto state = model.initialState();
  // Every 7th step only: the first sample at or after each whole second.
  const auto times = lineTimes(model, state, 0, 1000, 7);
  ASSERT_EQ(times.size(), 4u);  // the last, step 994, holds at 4.975 s: nothing at or after 5 s
  EXPECT_DOUBLE_EQ(times[0], 1.020);   // step 203
  EXPECT_DOUBLE_EQ(times[1], 2.000);   // step 399
  EXPECT_DOUBLE_EQ(times[2], 3.015);   // step 602
  EXPECT_DOUBLE_EQ(times[3], 4.030);   // step 805
}

TEST(DownforceLog, AGapOfMoreThanAPeriodSkipsTheSecondsWithoutSamples) {
  const DownforceLog model(DownforceLogParams{});
  auto state = model.initialState();
  EXPECT_TRUE(model.step(state, {2000.0, 2200.0}, 199 * kDt, kDt).due);  // 1.000 s
  const auto late = model.step(state, {2000.0, 2200.0}, 700 * kDt, kDt);  // holds at 3.505 s
  ASSERT_TRUE(late.due);
  EXPECT_DOUBLE_EQ(late.t_s, 3.505);
  EXPECT_FALSE(model.step(state, {2000.0, 2200.0}, 750 * kDt, kDt).due);  // 3.755 s
  EXPECT_TRUE(model.step(state, {2000.0, 2200.0}, 799 * kDt, kDt).due);   // 4.000 s
}

TEST(DownforceLog, AnOlderSampleAfterALineGivesNone) {
  const DownforceLog model(DownforceLogParams{});
  auto state = model.initialState();
  EXPECT_TRUE(model.step(state, {2000.0, 2200.0}, 199 * kDt, kDt).due);
  EXPECT_FALSE(model.step(state, {2000.0, 2200.0}, 198 * kDt, kDt).due);
  EXPECT_FALSE(model.step(state, {2000.0, 2200.0}, 199 * kDt, kDt).due);
}

TEST(DownforceLog, ThePeriodIsAParameter) {
  const DownforceLog model(DownforceLogParams{250'000'000});
  auto state = model.initialState();
  EXPECT_EQ(lineTimes(model, state, 0, 200), (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
}

TEST(DownforceLog, ANonPositivePeriodIsRefused) {
  EXPECT_THROW(DownforceLog(DownforceLogParams{0}), std::invalid_argument);
  EXPECT_THROW(DownforceLog(DownforceLogParams{-1}), std::invalid_argument);
}

}  // namespace
}  // namespace climbsim::downforce_log
