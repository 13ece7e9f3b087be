// The real clock and three real test participants, separate processes on real Fast DDS.

#include <gtest/gtest.h>

#include <set>

#include "climbsim/schedule.hpp"
#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

struct Member {
  std::string name;
  int period;
  int offset;
  std::string reads;
};

/// Three participants with different periods, each reading the others.
const std::vector<Member> kTrio = {{"a", 1, 0, "b,c"}, {"b", 2, 1, "a,c"}, {"c", 3, 2, "a,b"}};

std::string roster(const std::vector<Member>& members) {
  std::string out;
  for (const auto& m : members) out += (out.empty() ? "" : ",") + m.name;
  return out;
}

void startTrio(LockstepRun& run, const std::map<std::string, std::vector<std::string>>& extra = {}) {
  for (const auto& m : kTrio) {
    auto found = extra.find(m.name);
    run.startParticipant(m.name, m.period, m.offset, m.reads,
                         found == extra.end() ? std::vector<std::string>{} : found->second);
  }
}

/// Runs the trio for `steps` steps as fast as possible; returns each participant's record.
std::map<std::string, std::string> runTrio(const std::string& tag, int steps) {
  LockstepRun run(tag);
  run.startClock(roster(kTrio), {"--steps", std::to_string(steps), "--step-ms", "1"});
  startTrio(run);
  const auto codes = run.waitAll(120s);
  std::map<std::string, std::string> records;
  for (const auto& name : {"clock", "a", "b", "c"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  for (const auto& m : kTrio) records[m.name] = run.record(m.name);
  return records;
}

TEST(Lockstep, TwoThousandStepsExchangeStampedDataIdenticallyAcrossRuns) {
  constexpr int kSteps = 2000;
  const auto first = runTrio("trio-run1", kSteps);
  const auto second = runTrio("trio-run2", kSteps);
  std::map<std::string, Schedule> schedules;
  for (const auto& m : kTrio) schedules[m.name] = Schedule{static_cast<std::uint32_t>(m.period),
                                                           static_cast<std::uint32_t>(m.offset)};
  // value each producer wrote at each stamp, as seen by every consumer: must agree
  std::map<std::pair<std::string, std::uint64_t>, std::string> written;
  for (const auto& m : kTrio) {
    EXPECT_EQ(first.at(m.name), second.at(m.name)) << "participant " << m.name << " read different data";
    std::istringstream lines(first.at(m.name));
    std::uint64_t step = 0, stamp = 0;
    std::string source, value;
    std::map<std::string, std::uint64_t> count;
    std::set<std::uint64_t> steps_seen;
    while (lines >> step >> source >> stamp >> value) {
      // Zero-order hold: the producer's last due step before the consumer's step.
      ASSERT_EQ(schedules.at(source).lastDueBefore(step), stamp) << m.name << " at " << step << " from " << source;
      ASSERT_TRUE(schedules.at(m.name).isDue(step)) << m.name << " read at a step it is not due";
      auto [it, inserted] = written.emplace(std::make_pair(source, stamp), value);
      ASSERT_EQ(it->second, value) << "two consumers saw different values of " << source << "@" << stamp;
      ++count[source];
      steps_seen.insert(step);
    }
    // Every due step with a producer already due reads each producer exactly once.
    for (const auto& source : {"a", "b", "c"}) {
      if (m.reads.find(source) == std::string::npos) continue;
      std::uint64_t expected = 0;
      for (std::uint64_t k = 0; k < kSteps; ++k) {
        if (schedules.at(m.name).isDue(k) && schedules.at(source).lastDueBefore(k)) ++expected;
      }
      EXPECT_EQ(count[source], expected) << m.name << " reading " << source;
    }
  }
}

TEST(Lockstep, KillNineEndsTheRunWithin3SecondsNamingTheParticipant) {
  LockstepRun run("kill9");
  run.startClock(roster(kTrio), {"--steps", "100000000", "--step-ms", "1"});
  startTrio(run);
  Observer observer(run.domain());
  ASSERT_TRUE(observer.awaitSimTime([](const SimTime& t) { return t.step() >= 300; }, 60s)) << run.allLogs();
  run.process("b").signal(SIGKILL);
  const auto killed_at = Clock::now();
  const auto codes = run.waitAll(10s);
  const auto elapsed = Clock::now() - killed_at;
  for (const auto& name : {"clock", "a", "c"}) {
    ASSERT_TRUE(codes.count(name)) << name << " still runs\n" << run.allLogs();
    EXPECT_NE(codes.at(name), 0) << name;
  }
  EXPECT_LT(elapsed, 3s) << std::chrono::duration<double>(elapsed).count() << " s\n" << run.allLogs();
  std::cout << "every process ended " << std::chrono::duration<double>(elapsed).count() << " s after kill -9\n";
  EXPECT_NE(run.log("clock").find("participant 'b' vanished"), std::string::npos) << run.log("clock");
  EXPECT_NE(run.log("a").find("because of 'b'"), std::string::npos) << run.log("a");
  EXPECT_NE(run.log("c").find("because of 'b'"), std::string::npos) << run.log("c");
  const auto stop = observer.awaitStop(1s);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->first.kind(), STOP_FAILED);
  EXPECT_EQ(std::string(stop->first.culprit().c_str()), "b");
}

TEST(Lockstep, ParticipantMissingAtStartIsNamed) {
  LockstepRun run("missing");
  run.startClock(roster(kTrio), {"--steps", "100", "--start-timeout-s", "2"});
  run.startParticipant("a", 1, 0, "");
  run.startParticipant("b", 2, 1, "");
  const auto codes = run.waitAll(20s);
  ASSERT_EQ(codes.size(), 3u) << run.allLogs();
  EXPECT_EQ(codes.at("clock"), 3) << run.log("clock");
  EXPECT_NE(run.log("clock").find("missing participant c (never announced ready)"), std::string::npos)
      << run.log("clock");
  EXPECT_NE(codes.at("a"), 0);
  EXPECT_NE(run.log("a").find("because of 'c'"), std::string::npos) << run.log("a");
}

TEST(Lockstep, PauseSingleStepResumeAndStop) {
  LockstepRun run("pause");
  run.startClock(roster(kTrio), {"--steps", "100000000", "--step-ms", "1", "--start-paused"});
  startTrio(run);
  Observer observer(run.domain());
  auto paused_at = [](std::uint64_t step) {
    return [step](const SimTime& t) { return t.paused() && t.step() == step; };
  };
  ASSERT_TRUE(observer.awaitSimTime(paused_at(0), 60s)) << "the clock must hold before step 0\n" << run.allLogs();
  ASSERT_TRUE(observer.send(CLOCK_SINGLE_STEP, 5));
  ASSERT_TRUE(observer.awaitSimTime(paused_at(5), 10s)) << run.allLogs();
  ASSERT_TRUE(observer.send(CLOCK_SINGLE_STEP, 1));
  ASSERT_TRUE(observer.awaitSimTime(paused_at(6), 10s)) << "one step, then hold again";
  ASSERT_TRUE(observer.send(CLOCK_RESUME));
  ASSERT_TRUE(observer.awaitSimTime([](const SimTime& t) { return !t.paused() && t.step() > 500; }, 30s));
  ASSERT_TRUE(observer.send(CLOCK_PAUSE));
  const auto held = observer.awaitSimTime([](const SimTime& t) { return t.paused(); }, 10s);
  ASSERT_TRUE(held);
  const std::uint64_t k = held->first.step();
  ASSERT_TRUE(observer.send(CLOCK_SINGLE_STEP, 2));
  ASSERT_TRUE(observer.awaitSimTime(paused_at(k + 2), 10s)) << "the pause held at " << k;
  ASSERT_TRUE(observer.send(CLOCK_STOP));
  const auto codes = run.waitAll(20s);
  ASSERT_EQ(codes.size(), 4u) << run.allLogs();
  EXPECT_EQ(codes.at("clock"), 4) << "stopped on request\n" << run.log("clock");
  for (const auto& name : {"a", "b", "c"}) EXPECT_EQ(codes.at(name), 0) << run.log(name);
  // The participants computed exactly the granted steps: a (period 1) read up to step k + 1.
  const auto record = run.record("a");
  const auto last_line = record.substr(record.rfind('\n', record.size() - 2) + 1);
  EXPECT_EQ(std::stoull(last_line), k + 1) << last_line;
}

TEST(Lockstep, FailingParticipantStopsTheRunWithItsMessage) {
  LockstepRun run("fail");
  run.startClock(roster(kTrio), {"--steps", "1000"});
  startTrio(run, {{"c", {"--fail-at-step", "50"}}});
  const auto codes = run.waitAll(30s);
  ASSERT_EQ(codes.size(), 4u) << run.allLogs();
  EXPECT_EQ(codes.at("clock"), 1);
  EXPECT_EQ(codes.at("c"), 1);
  EXPECT_EQ(codes.at("a"), 1);
  // The step once, from the clock ("at step 50"), then the participant's own message.
  EXPECT_NE(run.log("clock").find("participant 'c' failed at step 50: failing on purpose at step 50"),
            std::string::npos)
      << run.log("clock");
  EXPECT_EQ(run.log("clock").find("step 50: step 50"), std::string::npos) << run.log("clock");
  EXPECT_NE(run.log("c").find("step 50: failing on purpose"), std::string::npos) << "its own log names the step";
}

TEST(Lockstep, WatchdogNamesAHangingParticipant) {
  LockstepRun run("watchdog");
  run.startClock(roster(kTrio), {"--steps", "1000", "--step-timeout-s", "1"});
  startTrio(run, {{"b", {"--hang-at-step", "21"}}});
  // b hangs for good; the clock and the others end.
  EXPECT_EQ(run.process("clock").waitFor(30s).value_or(-1), 1) << run.allLogs();
  EXPECT_EQ(run.process("a").waitFor(10s).value_or(-1), 1) << run.log("a");
  EXPECT_EQ(run.process("c").waitFor(10s).value_or(-1), 1) << run.log("c");
  // The clock knows b's acknowledged progress (in batches), at most the step it hangs in.
  const std::string clock_log = run.log("clock");
  const auto at = clock_log.find("watchdog: participant b made no progress past step ");
  ASSERT_NE(at, std::string::npos) << clock_log;
  const auto step = std::stoull(clock_log.substr(at + std::string("watchdog: participant b made no progress past step ").size()));
  EXPECT_LE(step, 21u) << clock_log;
  EXPECT_NE(clock_log.find("within 1 s"), std::string::npos) << clock_log;
  EXPECT_NE(run.log("a").find("because of 'b'"), std::string::npos) << run.log("a");
}

TEST(Lockstep, SameStepInputsReadTheProducersSampleOfTheSameStep) {
  LockstepRun run("same-step");
  run.startClock("a,b", {"--steps", "400", "--step-ms", "1", "--window-steps", "8"});
  run.startParticipant("a", 1, 0, "");
  run.startParticipant("b", 2, 1, "", {"--reads-same-step", "a"});
  const auto codes = run.waitAll(60s);
  for (const auto& name : {"clock", "a", "b"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  std::istringstream lines(run.record("b"));
  std::uint64_t step = 0, stamp = 0, rows = 0;
  std::string source, value;
  while (lines >> step >> source >> stamp >> value) {
    ASSERT_EQ(stamp, step) << "lag 0: b at step " << step << " reads a's sample of that step";
    ++rows;
  }
  EXPECT_EQ(rows, 200u);
}

TEST(Lockstep, AZeroLagCycleIsRefusedBeforeStepZeroNamingIt) {
  LockstepRun run("zero-lag-cycle");
  run.startClock("a,b", {"--steps", "100"});
  run.startParticipant("a", 1, 0, "", {"--reads-same-step", "b"});
  run.startParticipant("b", 1, 0, "", {"--reads-same-step", "a"});
  const auto codes = run.waitAll(30s);
  EXPECT_EQ(codes.count("clock") ? codes.at("clock") : -1, 2) << run.allLogs();
  EXPECT_NE(run.log("clock").find("a -(test/a)-> b -(test/b)-> a"), std::string::npos) << run.log("clock");
}

TEST(Lockstep, ParticipantNotOnTheRosterIsRejectedByName) {
  LockstepRun run("intruder");
  // Paused: the run cannot end before the intruder announces itself.
  run.startClock("a", {"--steps", "100", "--start-timeout-s", "20", "--start-paused"});
  run.startParticipant("a", 1, 0, "");
  run.startParticipant("zed", 1, 0, "");
  // The clock's verdict is the test: a participant that had not matched the clock's Stop before
  // the clock left waits out its own start timeout (the launcher stops it in a real run).
  const auto clock_code = run.process("clock").waitFor(30s);
  EXPECT_EQ(clock_code.value_or(-1), 2) << run.allLogs();
  EXPECT_NE(run.log("clock").find("participant 'zed'"), std::string::npos);
  EXPECT_NE(run.log("clock").find("is not on the roster (a)"), std::string::npos) << run.log("clock");
}

TEST(Lockstep, AStopOfTheRunsIdThatIsNotFromItsClockIsNotTakenBeforeTheRunStart) {
  // The run id is no secret once the clock has published RunStart, so an outsider may forge
  // a Stop with it; under load such a Stop can reach a participant before the participant's
  // own copy of the RunStart, and must not be taken. Made certain here: every participant has
  // acknowledged the forged Stop before the clock, and so any RunStart, exists.
  LockstepRun run("forged-early-stop");
  DdsSettings settings;
  settings.domain_id = run.domain();
  settings.qos_file = CLIMBSIM_QOS_FILE;
  Notifier notifier;
  DdsContext forger(settings, "forger");
  Writer<StopPubSubType> stop(forger, topic::kStop, qos::kLatched, notifier);
  Stop forged;
  forged.run_id(run.runId());
  forged.kind(STOP_FAILED);
  forged.culprit("a");
  forged.reason("a forged Stop of this run's id");
  stop.write(forged);
  startTrio(run);  // they wait for the clock
  const auto deadline = Clock::now() + 60s;
  while (stop.matchedReaders() < 3 && Clock::now() < deadline) {
    const auto seen = notifier.generation();
    if (stop.matchedReaders() >= 3) break;
    notifier.waitChanged(seen, deadline);
  }
  ASSERT_EQ(stop.matchedReaders(), 3) << run.allLogs();
  ASSERT_TRUE(stop.waitAcknowledged(30s)) << "the participants did not acknowledge the forged Stop";
  run.startClock(roster(kTrio), {"--steps", "200", "--step-ms", "1"});
  const auto codes = run.waitAll(120s);
  ASSERT_EQ(codes.size(), 4u) << run.allLogs();
  for (const auto& name : {"clock", "a", "b", "c"}) EXPECT_EQ(codes.at(name), 0) << name << "\n" << run.allLogs();
  for (const auto& m : kTrio) {
    EXPECT_NE(run.log(m.name).find("dropped a sample of 'clock/Stop' from writer"), std::string::npos)
        << m.name << " never saw the forged Stop\n" << run.log(m.name);
    EXPECT_EQ(run.log(m.name).find("a forged Stop"), std::string::npos) << run.log(m.name);
  }
}

TEST(Lockstep, AClockThatStopsTheRunBeforeStartingItIsBelievedOnceItLeaves) {
  // Its Stop comes before any RunStart: the participants take it when the clock has left
  // (it never made the run id public), and say why the run ended.
  LockstepRun run("stopped-before-start");
  run.startClock(roster(kTrio), {"--steps", "100", "--start-timeout-s", "3"});
  run.startParticipant("a", 1, 0, "");
  run.startParticipant("b", 2, 1, "");
  const auto codes = run.waitAll(30s);
  ASSERT_EQ(codes.size(), 3u) << run.allLogs();
  EXPECT_EQ(codes.at("clock"), 3) << run.log("clock");
  for (const auto& name : {"a", "b"}) {
    EXPECT_EQ(codes.at(name), 1) << run.log(name);
    EXPECT_NE(run.log(name).find("run failed because of 'c'"), std::string::npos) << run.log(name);
    EXPECT_EQ(run.log(name).find("vanished"), std::string::npos) << run.log(name);
  }
}

}  // namespace
}  // namespace climbsim::testing
