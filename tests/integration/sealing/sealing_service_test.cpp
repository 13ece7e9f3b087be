// climbsim-sealing in the lockstep with the real clock and a depth feeder that records the
// merged leakage: two shards give the unsharded leakage bit for bit; a bad depth image is
// dropped and the last valid leakage held.

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kSteps = 40;
constexpr int kBadAt = 20;

/// clock + feeder (recording) + `shards` sealing processes; returns the feeder's record.
std::string runSealing(const std::string& tag, int shards) {
  LockstepRun run(tag);
  std::string roster = "feeder";
  for (int i = 0; i < shards; ++i) roster += ",sealing" + std::to_string(i);
  run.startClock(roster, {"--steps", std::to_string(kSteps), "--step-ms", "5"});
  run.start("feeder", "climbsim-test-depth-feeder",
            {"--name", "feeder", "--seed", "11", "--bad-at", std::to_string(kBadAt), "--record",
             (run.dir() / "feeder.rec").string()});
  for (int i = 0; i < shards; ++i) {
    const std::string name = "sealing" + std::to_string(i);
    run.start(name, "climbsim-sealing",
              {"--name", name, "--shard", std::to_string(i) + "/" + std::to_string(shards), "--images",
               i == 0 ? "5" : "0"});
  }
  const auto codes = run.waitAll(120s);
  EXPECT_EQ(codes.count("clock") ? codes.at("clock") : -1, 0) << run.allLogs();
  EXPECT_EQ(codes.count("feeder") ? codes.at("feeder") : -1, 0) << run.allLogs();
  for (int i = 0; i < shards; ++i) {
    const std::string name = "sealing" + std::to_string(i);
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << run.allLogs();
    EXPECT_NE(run.log(name).find("dropped (1 so far)"), std::string::npos) << run.log(name);
  }
  return run.record("feeder");
}

struct Row {
  std::uint64_t stamp;
  std::string area, gap;
};

/// step -> segment -> (stamp, area, gap)
std::map<std::uint64_t, std::map<std::string, Row>> parse(const std::string& record) {
  std::map<std::uint64_t, std::map<std::string, Row>> out;
  std::istringstream lines(record);
  std::uint64_t step, stamp;
  std::string name, area, gap;
  while (lines >> step >> stamp >> name >> area >> gap) out[step][name] = Row{stamp, area, gap};
  return out;
}

TEST(SealingService, TwoShardsGiveTheUnshardedLeakageBitForBitAndABadImageIsHeld) {
  const std::string whole = runSealing("sealing-unsharded", 1);
  const std::string sharded = runSealing("sealing-sharded", 2);
  const auto rows = parse(whole);
  // Read at steps 1..kSteps-1: the sealing's outputs of steps 0..kSteps-2, 18 segments each.
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kSteps - 1)) << whole.substr(0, 2000);
  for (const auto& [step, segments] : rows) {
    ASSERT_EQ(segments.size(), 18u) << "step " << step;
    for (const auto& [name, row] : segments) ASSERT_EQ(row.stamp, step - 1);
  }
  // Random surfaces differ from step to step, and so does the leakage.
  std::set<std::string> distinct;
  for (const auto& [step, segments] : rows) distinct.insert(segments.at("outer1").area + segments.at("inner3").area);
  EXPECT_GT(distinct.size(), static_cast<std::size_t>(kSteps / 2));
  // The feeder's image of step kBadAt is bad: the sealing at kBadAt + 1 holds what it computed
  // at kBadAt (read at kBadAt + 1 and kBadAt + 2).
  for (const auto& [name, row] : rows.at(kBadAt + 2)) {
    EXPECT_EQ(row.area, rows.at(kBadAt + 1).at(name).area) << name;
    EXPECT_EQ(row.gap, rows.at(kBadAt + 1).at(name).gap) << name;
  }
  EXPECT_TRUE(sharded == whole) << "the merged leakage of two shards differs from one shard's";
}

}  // namespace
}  // namespace climbsim::testing
