// IDL <-> clock messages, without a network; the clock's words for a lost participant.

#include "clock_translate.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "clock_node.hpp"

namespace climbsim::clock {
namespace {

TEST(ClockTranslate, ReadyCarriesScheduleTopicsAndHashes) {
  climbsim::ParticipantReady idl;
  idl.participant("sealing-1");
  climbsim::RosterEntry entry;
  entry.participant("sealing-1");
  entry.period_steps(4);
  entry.offset_steps(1);
  entry.input_topics().push_back("DepthImage");
  entry.output_topics().push_back("Leakage");
  entry.same_step_inputs().push_back("DepthImage");
  entry.recorded_topics().push_back("RobotState");
  idl.entry(entry);
  climbsim::IdlHash hash;
  hash.file("sealing.idl");
  hash.sha256("abc123");
  idl.idl_hashes().push_back(hash);
  idl.host("node7");
  idl.pid(4242);

  const ReadyMsg msg = fromIdl(idl);
  EXPECT_EQ(msg.entry.participant, "sealing-1");
  EXPECT_EQ(msg.entry.schedule.period_steps, 4u);
  EXPECT_EQ(msg.entry.schedule.offset_steps, 1u);
  EXPECT_EQ(msg.entry.input_topics, std::vector<std::string>{"DepthImage"});
  EXPECT_EQ(msg.entry.output_topics, std::vector<std::string>{"Leakage"});
  EXPECT_EQ(msg.entry.same_step_inputs, std::vector<std::string>{"DepthImage"});
  EXPECT_EQ(msg.entry.recorded_topics, std::vector<std::string>{"RobotState"});
  ASSERT_EQ(msg.idl_hashes.size(), 1u);
  EXPECT_EQ(msg.idl_hashes[0].second, "abc123");
  EXPECT_EQ(msg.host, "node7");
  EXPECT_EQ(msg.pid, 4242u);

  const auto back = toIdl(msg.entry);
  EXPECT_EQ(back, entry);
}

TEST(ClockTranslate, DoneKindsAndControlCommandsMap) {
  climbsim::StepDone idl;
  idl.participant("x");
  idl.kind(climbsim::FAILED);
  idl.message("boom");
  idl.progress_step(17);
  idl.run_id(9);
  const auto done = fromIdl(idl);
  EXPECT_EQ(done.kind, DoneKind::kFailed);
  EXPECT_EQ(done.message, "boom");
  EXPECT_EQ(done.progress_step, 17u);
  EXPECT_EQ(done.run_id, 9u);
  idl.kind(climbsim::ARMED);
  EXPECT_EQ(fromIdl(idl).kind, DoneKind::kArmed);

  climbsim::ClockControl control;
  control.command(climbsim::CLOCK_SINGLE_STEP);
  control.steps(5);
  EXPECT_EQ(fromIdl(control).command, ControlCommand::kSingleStep);
  EXPECT_EQ(fromIdl(control).steps, 5u);
  control.command(climbsim::CLOCK_SET_REALTIME_FACTOR);
  control.realtime_factor(2.5);
  EXPECT_EQ(fromIdl(control).command, ControlCommand::kSetRealtimeFactor);
  EXPECT_DOUBLE_EQ(fromIdl(control).realtime_factor, 2.5);
}

TEST(ClockTranslate, StopAndGrantKeepEveryField) {
  StopMsg stop;
  stop.run_id = 3;
  stop.last_step = 99;
  stop.t_ns = 500'000'000;
  stop.kind = StopKind::kFailed;
  stop.culprit = "thermo";
  stop.reason = "participant 'thermo' vanished";
  const auto idl = toIdl(stop);
  EXPECT_EQ(idl.kind(), climbsim::STOP_FAILED);
  EXPECT_EQ(std::string(idl.culprit().c_str()), "thermo");
  EXPECT_EQ(std::string(idl.reason().c_str()), stop.reason);
  EXPECT_EQ(idl.last_step(), 99u);

  GrantMsg grant{3, 7, 35'000'000, 5'000'000};
  const auto g = toIdl(grant);
  EXPECT_EQ(g.horizon_step(), 7u);
  EXPECT_EQ(g.t_ns(), 35'000'000);
  EXPECT_EQ(g.dt_ns(), 5'000'000);
}

TEST(ClockTranslate, LongReasonsAreCutToTheIdlBound) {
  StopMsg stop;
  stop.reason = std::string(2000, 'x');
  EXPECT_EQ(std::string(toIdl(stop).reason().c_str()).size(), 511u);
}

}  // namespace
}  // namespace climbsim::clock

namespace climbsim::clock {
namespace {

TEST(LostWording, AStoppedProcessIsCalledStoppedNotGone) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    for (;;) ::pause();
  }
  ::kill(child, SIGSTOP);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, WUNTRACED), child);  // until it is stopped
  ASSERT_TRUE(WIFSTOPPED(status));
  const std::string stopped = lostWording(false, host, static_cast<std::uint32_t>(child));
  EXPECT_NE(stopped.find("its process " + std::to_string(child) + " is stopped (SIGSTOP"), std::string::npos) << stopped;
  EXPECT_EQ(stopped.find("left"), std::string::npos) << stopped;
  ::kill(child, SIGKILL);
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_EQ(lostWording(false, host, static_cast<std::uint32_t>(child)),
            "its process " + std::to_string(child) + " exited");
  const std::string running = lostWording(true, host, static_cast<std::uint32_t>(::getpid()));
  EXPECT_NE(running.find("liveliness lost; its process"), std::string::npos) << running;
  EXPECT_NE(running.find("runs but sends nothing"), std::string::npos) << running;
  // Another host's process is not looked up here.
  EXPECT_EQ(lostWording(true, "elsewhere", 42), "liveliness lost: its process 42 on elsewhere went silent");
  EXPECT_EQ(lostWording(false, "", 0), "DDS dropped it");
}

}  // namespace
}  // namespace climbsim::clock
