// Real-time factor 1.0: 5 s of simulation take 5 s of wall time within 2 %.

#include <gtest/gtest.h>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

TEST(Pacing, RealTimeFactorOneTakesTheSimulatedTimeOnTheWallClock) {
  LockstepRun run("rtf1");
  run.startClock("a,b,c", {"--duration-s", "5", "--step-ms", "5", "--rtf", "1.0"});
  run.startParticipant("a", 1, 0, "b,c");
  run.startParticipant("b", 2, 1, "a");
  run.startParticipant("c", 4, 3, "a,b");
  Observer observer(run.domain());
  // The first SimTime seen, moved back by its own simulated time, marks step 0's release.
  const auto first = observer.awaitSimTime([](const SimTime& t) { return !t.paused(); }, 60s);
  ASSERT_TRUE(first) << run.allLogs();
  const auto step0_at = first->second - std::chrono::nanoseconds(first->first.t_ns());
  const auto stop = observer.awaitStop(30s);
  ASSERT_TRUE(stop) << run.allLogs();
  EXPECT_EQ(stop->first.kind(), STOP_COMPLETED);
  const double wall_s = std::chrono::duration<double>(stop->second - step0_at).count();
  EXPECT_NEAR(wall_s, 5.0, 0.1) << "5 s simulated at factor 1.0";
  RecordProperty("wall_s", std::to_string(wall_s));
  std::cout << "5 s simulated took " << wall_s << " s of wall time\n";
  const auto codes = run.waitAll(10s);
  for (const auto& name : {"clock", "a", "b", "c"}) EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name;
}

}  // namespace
}  // namespace climbsim::testing
