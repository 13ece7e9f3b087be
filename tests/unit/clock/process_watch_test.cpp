// The clock's watch over the processes of its host's participants (process_watch.hpp), with
// real child processes.

#include "process_watch.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace climbsim::clock {
namespace {

/// A child that sleeps until it is killed.
pid_t sleeper() {
  const pid_t child = ::fork();
  if (child == 0) {
    for (;;) ::pause();
  }
  return child;
}

std::string thisHost() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return host;
}

/// A Fast DDS-style GUID prefix: vendor, host id, the pid's low 16 bits, random.
ParticipantId prefix(std::uint16_t host_id, std::uint32_t pid) {
  ParticipantId p;
  p.value[0] = 0x01;
  p.value[1] = 0x0f;
  p.value[2] = static_cast<std::uint8_t>(host_id & 0xFF);
  p.value[3] = static_cast<std::uint8_t>(host_id >> 8);
  p.value[4] = static_cast<std::uint8_t>(pid & 0xFF);
  p.value[5] = static_cast<std::uint8_t>((pid >> 8) & 0xFF);
  p.value[6] = 0x5a;
  return p;
}

TEST(ProcessWatch, AKilledProcessIsReportedOnceAndAStoppedOneNot) {
  const pid_t killed = sleeper();
  const pid_t stopped = sleeper();
  ASSERT_GT(killed, 0);
  ASSERT_GT(stopped, 0);
  ProcessWatch watch;
  watch.watch("b", static_cast<std::uint32_t>(killed));
  watch.watch("c", static_cast<std::uint32_t>(stopped));
  watch.watch("self", static_cast<std::uint32_t>(::getpid()));
  EXPECT_TRUE(watch.ended().empty());

  ::kill(stopped, SIGSTOP);
  int status = 0;
  ASSERT_EQ(::waitpid(stopped, &status, WUNTRACED), stopped);
  ::kill(killed, SIGKILL);
  // Not reaped yet: a zombie has ended as well.
  siginfo_t info{};
  ASSERT_EQ(::waitid(P_PID, static_cast<id_t>(killed), &info, WEXITED | WNOWAIT), 0);
  EXPECT_EQ(processState(static_cast<std::uint32_t>(killed)), 'Z');
  const auto ended = watch.ended();
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].first, "b");
  EXPECT_EQ(ended[0].second, static_cast<std::uint32_t>(killed));
  EXPECT_TRUE(watch.ended().empty()) << "reported twice";
  EXPECT_EQ(watch.size(), 2u);

  ASSERT_EQ(::waitpid(killed, &status, 0), killed);
  EXPECT_EQ(processState(static_cast<std::uint32_t>(killed)), 0);
  ::kill(stopped, SIGKILL);
  ASSERT_EQ(::waitpid(stopped, &status, 0), stopped);
  const auto later = watch.ended();
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0].first, "c");
}

TEST(ProcessWatch, AProcessStoppedForTheLimitIsReportedOnceAndOneThatGoesOnIsForgiven) {
  const pid_t stopped = sleeper();
  const pid_t paused = sleeper();
  ASSERT_GT(stopped, 0);
  ASSERT_GT(paused, 0);
  ProcessWatch watch;
  watch.watch("b", static_cast<std::uint32_t>(stopped));
  watch.watch("c", static_cast<std::uint32_t>(paused));
  int status = 0;
  for (const pid_t pid : {stopped, paused}) {
    ::kill(pid, SIGSTOP);
    ASSERT_EQ(::waitpid(pid, &status, WUNTRACED), pid);
  }
  // Seen stopped now; a limit of zero reports both at once, a long one neither.
  EXPECT_TRUE(watch.stoppedFor(std::chrono::hours(1)).empty());
  ::kill(paused, SIGCONT);
  ASSERT_EQ(::waitpid(paused, &status, WCONTINUED), paused);
  const auto named = watch.stoppedFor(std::chrono::seconds(0));
  ASSERT_EQ(named.size(), 1u) << "the continued process is no longer stopped";
  EXPECT_EQ(named[0].first, "b");
  EXPECT_EQ(named[0].second, static_cast<std::uint32_t>(stopped));
  EXPECT_TRUE(watch.stoppedFor(std::chrono::seconds(0)).empty()) << "reported twice";
  for (const pid_t pid : {stopped, paused}) {
    ::kill(pid, SIGKILL);
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  }
}

TEST(ProcessWatch, OnlyAParticipantThatEverythingPlacesOnThisHostIsWatched) {
  const pid_t child = sleeper();
  ASSERT_GT(child, 0);
  const auto pid = static_cast<std::uint32_t>(child);
  const ParticipantId ours = prefix(0x1234, static_cast<std::uint32_t>(::getpid()));
  EXPECT_TRUE(onThisHost(prefix(0x1234, pid), ours, thisHost(), pid));
  // Another host of the same name (another host id), another name, another pid in the GUID,
  // another vendor, no pid: the lease decides.
  EXPECT_FALSE(onThisHost(prefix(0x4321, pid), ours, thisHost(), pid));
  EXPECT_FALSE(onThisHost(prefix(0x1234, pid), ours, thisHost() + "-other", pid));
  EXPECT_FALSE(onThisHost(prefix(0x1234, pid + 1), ours, thisHost(), pid));
  ParticipantId cyclone = prefix(0x1234, pid);
  cyclone.value[1] = 0x10;
  EXPECT_FALSE(onThisHost(cyclone, ours, thisHost(), pid));
  EXPECT_FALSE(onThisHost(prefix(0x1234, 0), ours, thisHost(), 0));
  int status = 0;
  ::kill(child, SIGKILL);
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  // A pid with no process behind it when it announces.
  EXPECT_FALSE(onThisHost(prefix(0x1234, pid), ours, thisHost(), pid));
}

}  // namespace
}  // namespace climbsim::clock
