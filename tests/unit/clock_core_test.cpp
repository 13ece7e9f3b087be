// The clock's state machine with the transport faked and the wall time driven by the test.

#include "clock_core.hpp"

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"

namespace climbsim::clock {
namespace {

using namespace std::chrono_literals;

/// Records what the clock publishes.
class FakeTransport : public ClockTransport {
 public:
  void publishRunStart(const RunStartMsg& msg) override { run_starts.push_back(msg); }
  void publishGrant(const GrantMsg& msg) override { grants.push_back(msg); }
  void publishStop(const StopMsg& msg) override { stops.push_back(msg); }
  void publishSimTime(const SimTimeMsg& msg) override { sim_times.push_back(msg); }
  int grantReaders() const override { return grant_readers; }

  std::vector<RunStartMsg> run_starts;
  std::vector<GrantMsg> grants;
  std::vector<StopMsg> stops;
  std::vector<SimTimeMsg> sim_times;
  int grant_readers = 100;
};

ReadyMsg ready(const std::string& name, std::uint32_t period = 1, std::uint32_t offset = 0,
               std::vector<std::string> inputs = {}, std::vector<std::string> outputs = {}) {
  ReadyMsg msg;
  msg.entry.participant = name;
  msg.entry.schedule = Schedule{period, offset};
  msg.entry.input_topics = std::move(inputs);
  msg.entry.output_topics = std::move(outputs);
  msg.idl_hashes = {{"clock.idl", "aaaa"}};
  msg.host = "host";
  msg.pid = static_cast<std::uint32_t>(std::hash<std::string>{}(name) % 30000);
  return msg;
}

DoneMsg done(const std::string& name, std::uint64_t step, DoneKind kind = DoneKind::kStepDone,
             std::uint64_t run_id = 1) {
  DoneMsg msg;
  msg.participant = name;
  msg.run_id = run_id;
  msg.step = step;
  msg.kind = kind;
  return msg;
}

ControlMsg control(ControlCommand command, std::uint32_t steps = 1, double rtf = 0.0) {
  ControlMsg msg;
  msg.command = command;
  msg.steps = steps;
  msg.realtime_factor = rtf;
  msg.sender = "test";
  return msg;
}

class ClockCoreTest : public ::testing::Test {
 protected:
  ClockParams params(std::vector<std::string> roster, std::uint64_t end_step = 10) {
    ClockParams p;
    p.roster = std::move(roster);
    p.end_step = end_step;
    p.dt_ns = 5'000'000;
    p.start_timeout = 5s;
    p.step_timeout = 2s;
    p.run_id = 1;
    return p;
  }

  /// Brings a clock with these participants (all ready and armed) to running.
  std::unique_ptr<ClockCore> running(ClockParams p, const std::vector<ReadyMsg>& readies) {
    auto core = std::make_unique<ClockCore>(p, transport);
    core->start(now);
    for (const auto& r : readies) core->onReady(r, now);
    core->poll(now);
    for (const auto& r : readies) core->onDone(done(r.entry.participant, 0, DoneKind::kArmed), now);
    return core;
  }

  /// Answers every grant with Done from every due participant until the clock stops.
  void runToEnd(ClockCore& core) {
    for (int guard = 0; guard < 100000 && !core.finished(); ++guard) {
      const std::size_t before = transport.grants.size();
      const auto wake = core.poll(now);
      if (transport.grants.size() == before) {
        now = std::max(now, wake);  // nothing to answer: let wall time pass
      }
      for (std::size_t i = before; i < transport.grants.size(); ++i) {
        for (const auto& name : core.dueAt(transport.grants[i].step)) {
          core.onDone(done(name, transport.grants[i].step), now);
        }
      }
    }
  }

  /// Like runToEnd, but at most `rounds` poll rounds (for a clock that pauses).
  void runToEnd_limited(ClockCore& core, int rounds) {
    for (int i = 0; i < rounds && !core.finished(); ++i) {
      const std::size_t before = transport.grants.size();
      core.poll(now);
      for (std::size_t g = before; g < transport.grants.size(); ++g) {
        for (const auto& name : core.dueAt(transport.grants[g].step)) {
          core.onDone(done(name, transport.grants[g].step), now);
        }
      }
    }
  }

  FakeTransport transport;
  ClockCore::Time now = ClockCore::Time{} + 1000s;
};

TEST_F(ClockCoreTest, RejectsBadRosters) {
  EXPECT_THROW(ClockCore(params({}), transport), ConfigError);
  EXPECT_THROW(ClockCore(params({"a", "b", "a"}), transport), ConfigError);
  EXPECT_THROW(ClockCore(params({"a", "bad name"}), transport), ConfigError);
  auto p = params({"a"});
  p.dt_ns = 0;
  EXPECT_THROW(ClockCore(p, transport), ConfigError);
  p = params({"a"}, 0);
  EXPECT_THROW(ClockCore(p, transport), ConfigError);
  p = params({"a"});
  p.realtime_factor = -1;
  EXPECT_THROW(ClockCore(p, transport), ConfigError);
  try {
    ClockCore(params({"a", "b", "a"}), transport);
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'a' is named twice"), std::string::npos);
  }
}

TEST_F(ClockCoreTest, StartsOnlyWhenTheWholeRosterIsReady) {
  ClockCore core(params({"a", "b", "c"}), transport);
  core.start(now);
  core.onReady(ready("a"), now);
  core.onReady(ready("c"), now);
  core.poll(now);
  EXPECT_TRUE(transport.run_starts.empty());
  EXPECT_EQ(core.missingReady(), std::vector<std::string>{"b"});
  core.onReady(ready("b"), now);
  core.poll(now);
  ASSERT_EQ(transport.run_starts.size(), 1u);
  const auto& roster = transport.run_starts[0].roster;
  ASSERT_EQ(roster.size(), 3u);
  EXPECT_EQ(roster[0].participant, "a");
  EXPECT_EQ(roster[2].participant, "c");
  // No grant before everybody armed.
  core.onDone(done("a", 0, DoneKind::kArmed), now);
  core.onDone(done("b", 0, DoneKind::kArmed), now);
  core.poll(now);
  EXPECT_TRUE(transport.grants.empty());
  core.onDone(done("c", 0, DoneKind::kArmed), now);
  core.poll(now);
  ASSERT_EQ(transport.grants.size(), 1u);
  EXPECT_EQ(transport.grants[0].step, 0u);
}

TEST_F(ClockCoreTest, WaitsForEveryGrantReaderBeforeStepZero) {
  transport.grant_readers = 1;
  auto core = running(params({"a", "b"}), {ready("a"), ready("b")});
  core->poll(now);
  EXPECT_TRUE(transport.grants.empty());
  transport.grant_readers = 2;
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 1u);
}

TEST_F(ClockCoreTest, UnknownParticipantFailsTheRunNamingIt) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  core.onReady(ready("intruder"), now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_EQ(transport.stops.at(0).kind, StopKind::kFailed);
  EXPECT_EQ(transport.stops.at(0).culprit, "intruder");
  EXPECT_NE(transport.stops.at(0).reason.find("not on the roster (a, b)"), std::string::npos);
}

TEST_F(ClockCoreTest, TwoProcessesWithOneNameFailTheRun) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  auto first = ready("a");
  core.onReady(first, now);
  core.onReady(first, now);  // the same announcement again is fine
  EXPECT_FALSE(core.finished());
  auto second = ready("a");
  second.pid = first.pid + 1;
  core.onReady(second, now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_NE(transport.stops.at(0).reason.find("two processes announce the participant name 'a'"), std::string::npos);
}

TEST_F(ClockCoreTest, ZeroPeriodAnnouncedFailsNamingTheParticipant) {
  ClockCore core(params({"a"}), transport);
  core.start(now);
  core.onReady(ready("a", 0, 0), now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_EQ(transport.stops.at(0).culprit, "a");
  EXPECT_NE(transport.stops.at(0).reason.find("period_steps = 0"), std::string::npos);
}

TEST_F(ClockCoreTest, DifferentIdlFilesFailTheRun) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  core.onReady(ready("a"), now);
  auto b = ready("b");
  b.idl_hashes = {{"clock.idl", "bbbb"}};
  core.onReady(b, now);
  ASSERT_TRUE(core.finished());
  EXPECT_NE(transport.stops.at(0).reason.find("another clock.idl"), std::string::npos);
}

TEST_F(ClockCoreTest, InputWithoutProducerFailsAtStart) {
  ClockCore core(params({"sealing", "thermo"}), transport);
  core.start(now);
  core.onReady(ready("sealing", 1, 0, {"DepthImage"}, {"Leakage"}), now);
  core.onReady(ready("thermo", 1, 0, {"Leakage"}, {"AdhesionForce"}), now);
  core.poll(now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(transport.stops.at(0).culprit, "sealing");
  EXPECT_NE(transport.stops.at(0).reason.find("reads topic 'DepthImage'"), std::string::npos);
}

TEST_F(ClockCoreTest, StartTimeoutNamesTheMissingParticipants) {
  ClockCore core(params({"scene", "sealing", "thermo"}), transport);
  core.start(now);
  core.onReady(ready("sealing"), now);
  const auto wake = core.poll(now);
  EXPECT_LE(wake, now + 5s);
  EXPECT_FALSE(core.finished());
  core.poll(now + 4999ms);
  EXPECT_FALSE(core.finished());
  core.poll(now + 5s);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitStartTimeout);
  EXPECT_NE(transport.stops.at(0).reason.find("missing participants scene, thermo"), std::string::npos);
}

TEST_F(ClockCoreTest, StartTimeoutAlsoCoversArming) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  core.onReady(ready("a"), now);
  core.onReady(ready("b"), now);
  core.poll(now);
  core.onDone(done("a", 0, DoneKind::kArmed), now);
  core.poll(now + 6s);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitStartTimeout);
  EXPECT_EQ(transport.stops.at(0).culprit, "b");
}

TEST_F(ClockCoreTest, GrantsOnlyStepsWithSomebodyDueAndWaitsForAllOfThem) {
  auto core = running(params({"fast", "slow"}, 8), {ready("fast", 2, 0), ready("slow", 4, 1)});
  core->poll(now);
  ASSERT_EQ(transport.grants.size(), 1u);
  EXPECT_EQ(transport.grants[0].step, 0u);
  EXPECT_EQ(core->dueAt(0), std::vector<std::string>{"fast"});
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 1u) << "no grant before the due participant is done";
  core->onDone(done("fast", 0), now);
  core->poll(now);
  ASSERT_EQ(transport.grants.size(), 2u);
  EXPECT_EQ(transport.grants[1].step, 1u);  // slow at offset 1
  core->onDone(done("slow", 1), now);
  core->poll(now);
  EXPECT_EQ(transport.grants.back().step, 2u);
  core->onDone(done("fast", 2), now);
  // Steps 3 and 7 have nobody due: never granted, still counted in SimTime.
  runToEnd(*core);
  std::vector<std::uint64_t> granted;
  for (const auto& g : transport.grants) granted.push_back(g.step);
  EXPECT_EQ(granted, (std::vector<std::uint64_t>{0, 1, 2, 4, 5, 6}));
  EXPECT_EQ(transport.sim_times.size(), 8u);
  for (const auto& g : transport.grants) EXPECT_EQ(g.t_ns, static_cast<std::int64_t>(g.step) * 5'000'000);
}

TEST_F(ClockCoreTest, DueSetsFollowEveryPeriodAndOffset) {
  auto core = running(params({"a", "b", "c"}, 12), {ready("a", 1, 0), ready("b", 3, 1), ready("c", 4, 3)});
  EXPECT_EQ(core->dueAt(0), (std::vector<std::string>{"a"}));
  EXPECT_EQ(core->dueAt(1), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(core->dueAt(3), (std::vector<std::string>{"a", "c"}));
  EXPECT_EQ(core->dueAt(7), (std::vector<std::string>{"a", "b", "c"}));
}

TEST_F(ClockCoreTest, CompletesAtTheEndStep) {
  auto core = running(params({"a", "b"}, 50), {ready("a"), ready("b", 5, 2)});
  runToEnd(*core);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitOk);
  ASSERT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.stops[0].kind, StopKind::kCompleted);
  EXPECT_EQ(transport.stops[0].last_step, 49u);
  EXPECT_EQ(transport.grants.size(), 50u);
}

TEST_F(ClockCoreTest, StaleDonesDoNotAdvanceTheClock) {
  auto core = running(params({"a", "b"}), {ready("a"), ready("b")});
  core->poll(now);
  core->onDone(done("a", 0), now);
  core->onDone(done("b", 0, DoneKind::kStepDone, /*run_id=*/99), now);  // another run
  core->onDone(done("b", 5), now);                                       // another step
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 1u);
  core->onDone(done("b", 0), now);
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 2u);
}

TEST_F(ClockCoreTest, WatchdogNamesTheParticipantThatDidNotAnswer) {
  auto core = running(params({"a", "b", "c"}), {ready("a"), ready("b"), ready("c")});
  core->poll(now);
  core->onDone(done("a", 0), now);
  core->onDone(done("c", 0), now);
  const auto wake = core->poll(now + 1s);
  EXPECT_EQ(wake, now + 2s) << "the clock must wake up at the watchdog deadline";
  EXPECT_FALSE(core->finished());
  core->poll(now + 2s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFailed);
  EXPECT_EQ(transport.stops.at(0).culprit, "b");
  EXPECT_NE(transport.stops.at(0).reason.find("participant b did not finish step 0 within 2 s"), std::string::npos);
}

TEST_F(ClockCoreTest, LostParticipantEndsTheRunNamingIt) {
  auto core = running(params({"a", "b"}, 100), {ready("a"), ready("b")});
  core->poll(now);
  core->onDone(done("a", 0), now);
  core->onDone(done("b", 0), now);
  core->poll(now);
  core->onParticipantLost("b", "liveliness lost", now);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFailed);
  EXPECT_EQ(transport.stops.at(0).culprit, "b");
  EXPECT_NE(transport.stops.at(0).reason.find("vanished (liveliness lost) during step 1"), std::string::npos);
  // Nothing after the stop: later events are ignored, the stop is not repeated.
  core->onDone(done("a", 1), now);
  core->onControl(control(ControlCommand::kStop), now);
  core->poll(now);
  EXPECT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.grants.size(), 2u);
}

TEST_F(ClockCoreTest, FailedParticipantEndsTheRunWithItsMessage) {
  auto core = running(params({"a", "b"}), {ready("a"), ready("b")});
  core->poll(now);
  auto failed = done("a", 0, DoneKind::kFailed);
  failed.message = "depth image has NaN pixels";
  core->onDone(failed, now);
  ASSERT_TRUE(core->finished());
  EXPECT_NE(transport.stops.at(0).reason.find("participant 'a' failed at step 0: depth image has NaN pixels"),
            std::string::npos);
}

TEST_F(ClockCoreTest, StopFinishesTheStepInFlightAndIsIdempotent) {
  auto core = running(params({"a"}, 100), {ready("a")});
  core->poll(now);
  core->onDone(done("a", 0), now);
  core->poll(now);
  ASSERT_EQ(transport.grants.size(), 2u);  // step 1 in flight
  core->onControl(control(ControlCommand::kStop), now);
  core->onControl(control(ControlCommand::kStop), now);
  core->poll(now);
  EXPECT_FALSE(core->finished()) << "step 1 must finish first";
  core->onDone(done("a", 1), now);
  core->poll(now);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitStopped);
  EXPECT_EQ(transport.grants.size(), 2u) << "nobody starts step 2";
  ASSERT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.stops[0].kind, StopKind::kRequested);
  EXPECT_EQ(transport.stops[0].last_step, 1u);
}

TEST_F(ClockCoreTest, StopBeforeTheRunStartsEndsAtOnce) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  core.onReady(ready("a"), now);
  core.onControl(control(ControlCommand::kStop), now);
  core.poll(now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitStopped);
  EXPECT_TRUE(transport.grants.empty());
  EXPECT_EQ(transport.stops.at(0).kind, StopKind::kRequested);
}

TEST_F(ClockCoreTest, PauseSingleStepAndResume) {
  auto p = params({"a"}, 100);
  p.start_paused = true;
  auto core = running(p, {ready("a")});
  core->poll(now);
  EXPECT_TRUE(transport.grants.empty());
  ASSERT_EQ(transport.sim_times.size(), 1u);
  EXPECT_TRUE(transport.sim_times[0].paused);
  EXPECT_EQ(transport.sim_times[0].step, 0u);

  core->onControl(control(ControlCommand::kSingleStep, 3), now);
  runToEnd_limited(*core, 10);
  EXPECT_EQ(transport.grants.size(), 3u);
  EXPECT_TRUE(core->paused());
  EXPECT_TRUE(transport.sim_times.back().paused);
  EXPECT_EQ(transport.sim_times.back().step, 3u);

  core->onControl(control(ControlCommand::kResume), now);
  runToEnd(*core);
  EXPECT_EQ(transport.grants.size(), 100u);
  EXPECT_EQ(core->exitCode(), kExitOk);
}

TEST_F(ClockCoreTest, PauseTakesEffectAfterTheStepInFlight) {
  auto core = running(params({"a"}, 100), {ready("a")});
  core->poll(now);
  core->onControl(control(ControlCommand::kPause), now);
  core->onDone(done("a", 0), now);
  core->poll(now);
  core->poll(now + 10s);
  EXPECT_EQ(transport.grants.size(), 1u);
  EXPECT_TRUE(transport.sim_times.back().paused);
  EXPECT_EQ(transport.sim_times.back().step, 1u);
  EXPECT_FALSE(core->finished()) << "a paused clock is no watchdog case";
}

TEST_F(ClockCoreTest, RealTimeFactorPacesGrants) {
  auto p = params({"a"}, 1000);
  p.realtime_factor = 1.0;
  auto core = running(p, {ready("a")});
  const auto t0 = now;
  core->poll(now);  // step 0 at t0
  core->onDone(done("a", 0), now);
  const auto wake = core->poll(now);
  EXPECT_EQ(wake, t0 + 5ms) << "step 1 of 5 ms may start 5 ms after step 0";
  EXPECT_EQ(transport.grants.size(), 1u);
  core->poll(t0 + 5ms);
  EXPECT_EQ(transport.grants.size(), 2u);
  // Doubling the factor re-anchors: the next step comes 2.5 ms after the change.
  core->onDone(done("a", 1), t0 + 5ms);
  core->onControl(control(ControlCommand::kSetRealtimeFactor, 1, 2.0), t0 + 6ms);
  core->poll(t0 + 6ms);
  EXPECT_EQ(transport.grants.size(), 3u) << "re-anchored at the change: step 2 starts at once";
  core->onDone(done("a", 2), t0 + 6ms);
  EXPECT_EQ(core->poll(t0 + 6ms), t0 + 6ms + 2500us);
}

TEST_F(ClockCoreTest, PacedRunLastsItsSimulatedTime) {
  auto p = params({"a"}, 200);
  p.realtime_factor = 1.0;
  auto core = running(p, {ready("a")});
  const auto t0 = now;
  runToEnd(*core);
  EXPECT_EQ(now - t0, 1s) << "200 steps of 5 ms at factor 1 end 1 s after the start";
}

}  // namespace
}  // namespace climbsim::clock
