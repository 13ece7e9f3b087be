// The clock's state machine with the transport faked and the wall time driven by the test.

#include "clock_core.hpp"

#include <gtest/gtest.h>

#include <map>
#include <memory>

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

/// A participant's acknowledgement: every due step below `step` is done.
DoneMsg done(const std::string& name, std::uint64_t step, DoneKind kind = DoneKind::kStepDone,
             std::uint64_t run_id = 1) {
  DoneMsg msg;
  msg.participant = name;
  msg.run_id = run_id;
  msg.progress_step = step;
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
    end_step = p.end_step;
    auto core = std::make_unique<ClockCore>(p, transport);
    core->start(now);
    for (const auto& r : readies) {
      core->onReady(r, now);
      schedules[r.entry.participant] = r.entry.schedule;
    }
    core->poll(now);
    for (const auto& r : readies) core->onDone(done(r.entry.participant, 0, DoneKind::kArmed), now);
    return core;
  }

  /// The newest horizon granted (0: none).
  std::uint64_t horizon() const { return transport.grants.empty() ? 0 : transport.grants.back().horizon_step; }

  /// Every participant computes all its due steps below the newest horizon and says so.
  void everyoneReachesTheHorizon(ClockCore& core) {
    for (const auto& [name, schedule] : schedules) {
      core.onDone(done(name, std::min(schedule.nextDueFrom(horizon()), end_step)), now);
    }
  }

  /// Answers every new horizon until the clock stops; lets wall time pass when idle.
  void runToEnd(ClockCore& core, int rounds = 100000) {
    for (int guard = 0; guard < rounds && !core.finished(); ++guard) {
      everyoneReachesTheHorizon(core);
      const std::size_t before = transport.grants.size();
      const auto wake = core.poll(now);
      if (transport.grants.size() == before) {
        now = std::max(now, wake);  // nothing to answer: let wall time pass
      }
    }
  }

  std::map<std::string, Schedule> schedules;
  std::uint64_t end_step = 0;
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
  EXPECT_EQ(transport.grants[0].horizon_step, 1u) << "W = 1 by default: one step at a time";
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

TEST_F(ClockCoreTest, TwoWritersOfAControllerCommandAreRefusedAtStartNamingBoth) {
  // The docs' Python controller started beside the reference controller without
  // `controller: {type: external}`: both would write the valve commands.
  ClockCore core(params({"controller", "py-controller", "thermo"}), transport);
  core.start(now);
  core.onReady(ready("controller", 1, 0, {"thermo/ChamberState"}, {"controller/ValveCommand", "controller/DriveCommand"}),
               now);
  core.onReady(ready("py-controller", 1, 0, {"thermo/ChamberState"}, {"controller/ValveCommand"}), now);
  core.onReady(ready("thermo", 1, 0, {"controller/ValveCommand"}, {"thermo/ChamberState"}), now);
  core.poll(now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_TRUE(transport.run_starts.empty()) << "refused before the run starts";
  const std::string reason = transport.stops.at(0).reason;
  EXPECT_NE(reason.find("participants 'controller' and 'py-controller' both write topic 'controller/ValveCommand'"),
            std::string::npos)
      << reason;
  EXPECT_NE(reason.find("controller: {type: external}"), std::string::npos) << reason;
}

TEST_F(ClockCoreTest, SeveralWritersOfADataTopicAreFine) {
  // Sealing shards each write their part of the leakage.
  ClockCore core(params({"sealing-0", "sealing-1", "thermo"}), transport);
  core.start(now);
  core.onReady(ready("sealing-0", 1, 0, {}, {"sealing/Leakage"}), now);
  core.onReady(ready("sealing-1", 1, 0, {}, {"sealing/Leakage"}), now);
  core.onReady(ready("thermo", 1, 0, {"sealing/Leakage"}, {}), now);
  core.poll(now);
  EXPECT_FALSE(core.finished());
  EXPECT_TRUE(transport.stops.empty());
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

TEST_F(ClockCoreTest, WindowOneIsOneGrantPerStep) {
  auto core = running(params({"fast", "slow"}, 8), {ready("fast", 2, 0), ready("slow", 4, 1)});
  core->poll(now);
  ASSERT_EQ(horizon(), 1u);
  core->onDone(done("fast", 2), now);  // did step 0; next due at 2
  core->poll(now);
  ASSERT_EQ(horizon(), 2u) << "slow (due at 1) is the slowest now: H = 1 + 1";
  core->onDone(done("slow", 5), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 3u);
  runToEnd(*core);
  std::vector<std::uint64_t> horizons;
  for (const auto& g : transport.grants) horizons.push_back(g.horizon_step);
  // Nobody is due at 3 or 7: progress jumps over them (fast 0 2 4 6, slow 1 5).
  EXPECT_EQ(horizons, (std::vector<std::uint64_t>{1, 2, 3, 5, 6, 7}));
  for (const auto& g : transport.grants) EXPECT_EQ(g.t_ns, static_cast<std::int64_t>(g.horizon_step) * 5'000'000);
  EXPECT_EQ(core->exitCode(), kExitOk);
}

TEST_F(ClockCoreTest, DueSetsFollowEveryPeriodAndOffset) {
  auto core = running(params({"a", "b", "c"}, 12), {ready("a", 1, 0), ready("b", 3, 1), ready("c", 4, 3)});
  EXPECT_EQ(core->dueAt(0), (std::vector<std::string>{"a"}));
  EXPECT_EQ(core->dueAt(1), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(core->dueAt(3), (std::vector<std::string>{"a", "c"}));
  EXPECT_EQ(core->dueAt(7), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(core->progressOf("b"), 1u) << "progress starts at the first due step";
  EXPECT_EQ(core->progressOf("c"), 3u);
}

TEST_F(ClockCoreTest, HorizonRunsAWindowAheadOfTheSlowest) {
  auto p = params({"fast", "slow"}, 100);
  p.window_steps = 8;
  auto core = running(p, {ready("fast"), ready("slow")});
  core->poll(now);
  ASSERT_EQ(horizon(), 8u);
  core->onDone(done("fast", 8), now);  // fast waits at the horizon
  core->onDone(done("slow", 4), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 12u) << "slowest progress 4 + W 8";
  core->onDone(done("slow", 5), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 12u) << "less than W/2 more, and nobody waits at the horizon: no grant";
  core->onDone(done("fast", 12), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 12u) << "fast waits, but the slowest has room: the next grant waits for W/2";
  core->onDone(done("slow", 9), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 17u);
  EXPECT_EQ(core->reachedStep(), 9u);
  core->onDone(done("slow", 12), now);
  core->onDone(done("fast", 17), now);
  core->onDone(done("slow", 17), now);
  core->poll(now);
  EXPECT_EQ(horizon(), 25u) << "everyone waits at the horizon: a grant at once";
}

TEST_F(ClockCoreTest, GrantsComeInStridesOfHalfTheWindow) {
  auto p = params({"a", "b"}, 160);
  p.window_steps = 16;
  auto core = running(p, {ready("a"), ready("b", 4, 1)});
  runToEnd(*core);
  EXPECT_EQ(core->exitCode(), kExitOk);
  EXPECT_EQ(transport.stops.at(0).last_step, 159u);
  EXPECT_LE(transport.grants.size(), 160u / 8 + 1) << "one grant per W/2 steps, not per step";
  for (std::size_t i = 1; i < transport.grants.size(); ++i) {
    EXPECT_GT(transport.grants[i].horizon_step, transport.grants[i - 1].horizon_step) << "the horizon only grows";
  }
  // Everything here happens at one instant of wall time: SimTime with the first and the last.
  ASSERT_EQ(transport.sim_times.size(), 2u) << "SimTime at most every 1/30 s, always the first and last horizon";
}

TEST_F(ClockCoreTest, SimTimeGoesOutAtMostThirtyTimesASecondOfWallTimeAndWithTheLastHorizon) {
  auto p = params({"a"}, 2000);
  p.window_steps = 4;  // a grant every 2 to 4 steps
  auto core = running(p, {ready("a")});
  const auto t0 = now;
  std::vector<ClockCore::Time> sent_at;
  for (int guard = 0; guard < 100000 && !core->finished(); ++guard) {
    everyoneReachesTheHorizon(*core);
    const std::size_t before = transport.sim_times.size();
    core->poll(now);
    if (transport.sim_times.size() != before) sent_at.push_back(now);
    now += 1ms;  // a horizon about every millisecond: 500 steps a second of wall time
  }
  ASSERT_TRUE(core->finished());
  ASSERT_GE(transport.grants.size(), 400u);
  const double wall_s = std::chrono::duration<double>(now - t0).count();
  EXPECT_LE(transport.sim_times.size(), static_cast<std::size_t>(wall_s * 30.0) + 2) << wall_s << " s";
  EXPECT_GE(transport.sim_times.size(), static_cast<std::size_t>(wall_s * 30.0 * 0.8)) << "not thinned to nothing";
  for (std::size_t i = 1; i + 1 < sent_at.size(); ++i) {
    EXPECT_GE(sent_at[i] - sent_at[i - 1], 33ms) << "only the last may come sooner, at " << i;
  }
  EXPECT_EQ(transport.grants.back().horizon_step, 2000u);
  EXPECT_GE(transport.sim_times.back().step, 1996u) << "the last horizon's SimTime: where the run ends";
}

TEST_F(ClockCoreTest, ProgressBeyondTheHorizonIsAProtocolViolation) {
  auto p = params({"a", "b"}, 100);
  p.window_steps = 4;
  auto core = running(p, {ready("a"), ready("b", 8, 3)});
  core->poll(now);
  ASSERT_EQ(horizon(), 4u);
  core->onDone(done("b", 11), now);  // did step 3; next due 11: nothing due in between
  EXPECT_FALSE(core->finished());
  core->onDone(done("a", 9), now);  // a is due at every step: 4..8 were not granted
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(transport.stops.at(0).culprit, "a");
  EXPECT_NE(transport.stops.at(0).reason.find("beyond the horizon 4"), std::string::npos);
}

TEST_F(ClockCoreTest, CompletesAtTheEndStep) {
  auto core = running(params({"a", "b"}, 50), {ready("a"), ready("b", 5, 2)});
  runToEnd(*core);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitOk);
  ASSERT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.stops[0].kind, StopKind::kCompleted);
  EXPECT_EQ(transport.stops[0].last_step, 49u);
  EXPECT_EQ(horizon(), 50u);
}

TEST_F(ClockCoreTest, StaleDonesDoNotAdvanceTheClock) {
  auto core = running(params({"a", "b"}), {ready("a"), ready("b")});
  core->poll(now);
  core->onDone(done("a", 1), now);
  core->onDone(done("b", 1, DoneKind::kStepDone, /*run_id=*/99), now);  // another run
  core->onDone(done("b", 0), now);                                       // old news
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 1u);
  core->onDone(done("b", 1), now);
  core->poll(now);
  EXPECT_EQ(transport.grants.size(), 2u);
}

TEST_F(ClockCoreTest, WatchdogNamesTheParticipantThatMadeNoProgress) {
  auto p = params({"a", "b", "c"});
  p.window_steps = 4;
  auto core = running(p, {ready("a"), ready("b"), ready("c")});
  core->poll(now);
  core->onDone(done("a", 4), now);
  core->onDone(done("c", 4), now);
  const auto wake = core->poll(now + 1s);
  EXPECT_EQ(wake, now + 2s) << "the clock must wake up at the watchdog deadline";
  EXPECT_FALSE(core->finished());
  core->poll(now + 2s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFailed);
  EXPECT_EQ(transport.stops.at(0).culprit, "b");
  EXPECT_NE(transport.stops.at(0).reason.find("participant b made no progress past step 0 within 2 s"),
            std::string::npos);
}

TEST_F(ClockCoreTest, WatchdogBlamesRecordersOnlyWhenNobodyElseHasWork) {
  auto p = params({"producer", "recorder", "other"}, 100);
  p.window_steps = 8;
  auto rec = ready("recorder", 1, 0, {}, {});
  rec.entry.recorded_topics = {"t"};
  auto core = running(p, {ready("producer", 1, 0, {}, {"t"}), rec, ready("other")});
  core->poll(now);
  core->onDone(done("producer", 3), now);  // then hangs inside step 3 with its batch unsent
  core->onDone(done("other", 8), now);
  core->onDone(done("recorder", 1), now);  // waits for the producer's batch
  core->poll(now);
  core->poll(now + 2s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(transport.stops.at(0).culprit, "producer");
}

TEST_F(ClockCoreTest, WatchdogBlamesAHungRecorder) {
  auto p = params({"producer", "recorder"}, 100);
  p.window_steps = 8;
  auto rec = ready("recorder");
  rec.entry.recorded_topics = {"t"};
  auto core = running(p, {ready("producer", 1, 0, {}, {"t"}), rec});
  core->poll(now);
  core->onDone(done("producer", 8), now);
  core->poll(now + 2s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(transport.stops.at(0).culprit, "recorder");
}

TEST_F(ClockCoreTest, LostParticipantEndsTheRunNamingIt) {
  auto core = running(params({"a", "b"}, 100), {ready("a"), ready("b")});
  core->poll(now);
  core->onDone(done("a", 1), now);
  core->onDone(done("b", 1), now);
  core->poll(now);
  core->onParticipantLost("b", "liveliness lost", now);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFailed);
  EXPECT_EQ(transport.stops.at(0).culprit, "b");
  EXPECT_NE(transport.stops.at(0).reason.find("vanished (liveliness lost) at step 1"), std::string::npos);
  // Nothing after the stop: later events are ignored, the stop is not repeated.
  core->onDone(done("a", 2), now);
  core->onControl(control(ControlCommand::kStop), now);
  core->poll(now);
  EXPECT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.grants.size(), 2u);
}

TEST_F(ClockCoreTest, AStalledHandshakeBeforeTheRunGivesTheStartUpNamingTheParticipant) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  core.onReady(ready("a"), now);
  core.onStartStalled("intruder", "not on the roster: ignored");
  EXPECT_FALSE(core.finished());
  core.onStartStalled("b", "the DDS Security handshake between 'clock' and 'b' has not ended");
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitRetryStart) << "nothing was computed: the run can start again";
  ASSERT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.stops[0].kind, StopKind::kFailed);
  EXPECT_EQ(transport.stops[0].culprit, "b");
  EXPECT_NE(transport.stops[0].reason.find("handshake between 'clock' and 'b'"), std::string::npos);
  EXPECT_TRUE(transport.run_starts.empty());
}

TEST_F(ClockCoreTest, AStalledHandshakeReportedOnceRunningChangesNothing) {
  auto core = running(params({"a", "b"}), {ready("a"), ready("b")});
  core->poll(now);
  ASSERT_EQ(core->phase(), ClockPhase::kRunning);
  core->onStartStalled("b", "late");
  EXPECT_FALSE(core->finished()) << "a running run has every handshake it needs";
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

TEST_F(ClockCoreTest, StopFreezesTheHorizonAndEndsWhenEveryoneReachedIt) {
  auto p = params({"a", "b"}, 100);
  p.window_steps = 8;
  auto core = running(p, {ready("a"), ready("b")});
  core->poll(now);
  ASSERT_EQ(horizon(), 8u);
  core->onControl(control(ControlCommand::kStop), now);
  core->onControl(control(ControlCommand::kStop), now);
  core->onDone(done("a", 8), now);
  core->onDone(done("b", 6), now);
  core->poll(now);
  EXPECT_FALSE(core->finished()) << "b must finish steps 6 and 7 first";
  EXPECT_EQ(horizon(), 8u) << "no new horizon after the stop";
  core->onDone(done("b", 8), now);
  core->poll(now);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitStopped);
  ASSERT_EQ(transport.stops.size(), 1u);
  EXPECT_EQ(transport.stops[0].kind, StopKind::kRequested);
  EXPECT_EQ(transport.stops[0].last_step, 7u) << "exact: every participant computed every due step up to it";
  EXPECT_EQ(transport.grants.size(), 1u);
}

TEST_F(ClockCoreTest, AFallEndsTheRunLikeAStopWithItsOwnOutcome) {
  auto p = params({"drive", "recorder"}, 1000);
  p.window_steps = 8;
  auto core = running(p, {ready("drive"), ready("recorder")});
  core->poll(now);
  ASSERT_EQ(horizon(), 8u);
  auto fell = done("drive", 5, DoneKind::kFell);
  fell.message = "FELL at t = 0.030 s: the robot left the wall";
  core->onDone(fell, now);
  core->onDone(done("drive", 8), now);
  core->onDone(done("recorder", 6), now);
  core->poll(now);
  EXPECT_FALSE(core->finished()) << "the recorder still writes the rows below the frozen horizon";
  core->onDone(done("recorder", 8), now);
  core->poll(now);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFell);
  EXPECT_EQ(transport.stops.at(0).kind, StopKind::kFell);
  EXPECT_EQ(transport.stops.at(0).culprit, "drive");
  EXPECT_EQ(transport.stops.at(0).reason, fell.message);
  EXPECT_EQ(transport.stops.at(0).last_step, 7u);
  EXPECT_EQ(transport.grants.size(), 1u);
}

TEST_F(ClockCoreTest, StopWaitsWithTheWatchdog) {
  auto p = params({"a"}, 100);
  p.window_steps = 8;
  auto core = running(p, {ready("a")});
  core->poll(now);
  core->onControl(control(ControlCommand::kStop), now);
  core->poll(now + 2s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitFailed) << "a participant that never reaches the frozen horizon fails the run";
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
  p.window_steps = 16;
  auto core = running(p, {ready("a")});
  core->poll(now);
  EXPECT_TRUE(transport.grants.empty());
  ASSERT_EQ(transport.sim_times.size(), 1u);
  EXPECT_TRUE(transport.sim_times[0].paused);
  EXPECT_EQ(transport.sim_times[0].step, 0u);

  core->onControl(control(ControlCommand::kSingleStep, 3), now);
  runToEnd(*core, 10);
  EXPECT_EQ(horizon(), 3u) << "single step 3: H += 3";
  EXPECT_TRUE(core->paused());
  core->poll(now + 1s);
  EXPECT_TRUE(transport.sim_times.back().paused);
  EXPECT_EQ(transport.sim_times.back().step, 3u);
  core->onControl(control(ControlCommand::kSingleStep, 2), now + 1s);
  runToEnd(*core, 10);
  EXPECT_EQ(horizon(), 5u);

  core->onControl(control(ControlCommand::kResume), now);
  runToEnd(*core);
  EXPECT_EQ(horizon(), 100u);
  EXPECT_EQ(core->exitCode(), kExitOk);
}

TEST_F(ClockCoreTest, PauseFreezesTheHorizonAndIsNoWatchdogCase) {
  auto p = params({"a"}, 100);
  p.window_steps = 8;
  auto core = running(p, {ready("a")});
  core->poll(now);
  ASSERT_EQ(horizon(), 8u);
  core->onControl(control(ControlCommand::kPause), now);
  core->onDone(done("a", 8), now);  // finishes what was granted before the pause
  core->poll(now);
  core->poll(now + 10s);
  EXPECT_EQ(transport.grants.size(), 1u);
  EXPECT_TRUE(transport.sim_times.back().paused);
  EXPECT_EQ(transport.sim_times.back().step, 8u);
  EXPECT_FALSE(core->finished()) << "a paused clock is no watchdog case";
  core->onControl(control(ControlCommand::kResume), now + 10s);
  core->poll(now + 10s);
  EXPECT_EQ(horizon(), 16u);
  core->poll(now + 11s);
  EXPECT_FALSE(core->finished()) << "the watchdog counts from the resume";
}

TEST_F(ClockCoreTest, APauseNobodyResumesWithinMaxPauseEndsTheRunWithTheReason) {
  auto p = params({"a"}, 100);
  p.window_steps = 8;
  p.max_pause = 5s;
  auto core = running(p, {ready("a")});
  core->poll(now);
  core->onControl(control(ControlCommand::kPause), now);
  core->onDone(done("a", 8), now);
  core->poll(now + 4s);
  EXPECT_FALSE(core->finished()) << "4 s of a 5 s allowance";
  core->onControl(control(ControlCommand::kSingleStep, 1), now + 4s);  // someone is there: the allowance restarts
  core->poll(now + 4s);
  ASSERT_EQ(horizon(), 9u);
  core->onDone(done("a", 9), now + 4s);
  core->poll(now + 8s);
  EXPECT_FALSE(core->finished()) << "4 s since the single step";
  const auto next = core->poll(now + 8s);
  EXPECT_LE(next, now + 9s) << "the clock wakes for the end of the allowance";
  core->poll(now + 9s);
  ASSERT_TRUE(core->finished());
  EXPECT_EQ(core->exitCode(), kExitStopped);
  EXPECT_EQ(transport.stops.back().kind, StopKind::kRequested);
  EXPECT_NE(transport.stops.back().reason.find("paused for 5 s and nobody resumed it (clock.max_pause_s)"),
            std::string::npos)
      << transport.stops.back().reason;
  EXPECT_NE(transport.stops.back().reason.find("after step 8"), std::string::npos) << transport.stops.back().reason;
}

TEST_F(ClockCoreTest, WithoutMaxPauseAPauseLastsForEver) {
  auto p = params({"a"}, 100);
  p.start_paused = true;
  auto core = running(p, {ready("a")});
  core->poll(now + 3600s);
  EXPECT_FALSE(core->finished());
  EXPECT_TRUE(core->paused());
}

TEST_F(ClockCoreTest, RealTimeFactorPacesTheHorizon) {
  auto p = params({"a"}, 1000);
  p.realtime_factor = 1.0;
  p.window_steps = 16;
  auto core = running(p, {ready("a")});
  const auto t0 = now;
  core->poll(now);  // step 0 at t0
  ASSERT_EQ(horizon(), 1u);
  core->onDone(done("a", 1), now);
  const auto wake = core->poll(now);
  EXPECT_EQ(wake, t0 + 5ms) << "step 1 of 5 ms may start 5 ms after step 0";
  EXPECT_EQ(horizon(), 1u);
  core->poll(t0 + 5ms);
  EXPECT_EQ(horizon(), 2u);
  core->poll(t0 + 12ms);
  EXPECT_EQ(horizon(), 3u) << "steps 0..2 have started by 12 ms";
  // Doubling the factor re-anchors: the next step comes 2.5 ms after the change.
  core->onControl(control(ControlCommand::kSetRealtimeFactor, 1, 2.0), t0 + 13ms);
  core->poll(t0 + 13ms);
  EXPECT_EQ(horizon(), 4u) << "re-anchored at the change: step 3 starts at once";
  EXPECT_EQ(core->poll(t0 + 13ms), t0 + 13ms + 2500us);
}

TEST_F(ClockCoreTest, PacedRunLastsItsSimulatedTime) {
  auto p = params({"a"}, 200);
  p.realtime_factor = 1.0;
  p.window_steps = 16;
  auto core = running(p, {ready("a")});
  const auto t0 = now;
  runToEnd(*core);
  EXPECT_EQ(now - t0, 1s) << "200 steps of 5 ms at factor 1 end 1 s after the start";
  EXPECT_EQ(core->exitCode(), kExitOk);
}

TEST_F(ClockCoreTest, ZeroLagCycleIsRefusedNamingIt) {
  ClockCore core(params({"a", "b", "c"}), transport);
  core.start(now);
  auto a = ready("a", 1, 0, {"tb"}, {"ta"});
  a.entry.same_step_inputs = {"tb"};
  auto b = ready("b", 1, 0, {"ta"}, {"tb"});
  b.entry.same_step_inputs = {"ta"};
  core.onReady(a, now);
  core.onReady(b, now);
  core.onReady(ready("c", 1, 0, {"ta"}, {}), now);
  core.poll(now);
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_NE(transport.stops.at(0).reason.find("a -(ta)-> b -(tb)-> a"), std::string::npos)
      << transport.stops.at(0).reason;
}

TEST_F(ClockCoreTest, ZeroLagChainWithoutACycleRuns) {
  ClockCore core(params({"a", "b"}), transport);
  core.start(now);
  auto b = ready("b", 1, 0, {"ta"}, {"tb"});
  b.entry.same_step_inputs = {"ta"};
  core.onReady(ready("a", 1, 0, {"tb"}, {"ta"}), now);  // a reads b one step late: no cycle
  core.onReady(b, now);
  core.poll(now);
  EXPECT_FALSE(core.finished());
  ASSERT_EQ(transport.run_starts.size(), 1u);
  EXPECT_EQ(transport.run_starts[0].roster.at(1).same_step_inputs, std::vector<std::string>{"ta"});
}

TEST_F(ClockCoreTest, ParticipantBuiltFromAnotherProtocolThanTheClockIsRefused) {
  auto p = params({"a"});
  p.idl_hashes = {{"clock.idl", "cccc"}};
  ClockCore core(p, transport);
  core.start(now);
  core.onReady(ready("a"), now);  // built from clock.idl "aaaa"
  ASSERT_TRUE(core.finished());
  EXPECT_EQ(core.exitCode(), kExitConfig);
  EXPECT_NE(transport.stops.at(0).reason.find("another clock.idl than the clock"), std::string::npos);
}

TEST_F(ClockCoreTest, WindowMustFitTheQueues) {
  auto p = params({"a"});
  p.window_steps = 0;
  EXPECT_THROW(ClockCore(p, transport), ConfigError);
  p.window_steps = 40;
  p.max_window_steps = 32;
  EXPECT_THROW(ClockCore(p, transport), ConfigError);
  p.window_steps = 32;
  EXPECT_NO_THROW(ClockCore(p, transport));
}

}  // namespace
}  // namespace climbsim::clock
