// Nobody outside the run can steer it (the security tests): a real Fast DDS participant of its own
// (climbsim-test-outsider, a separate process) on the run's domain replays every attack the
// issue found, and the run must give the trace of an undisturbed run, bit for bit.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include "climbsim/domain_lease.hpp"
#include "launcher_run.hpp"

namespace {

using namespace climbsim::system_test;

/// The scenario both runs use: long enough that the outsider attacks mid-run (from step 100)
/// and its samples reach the services while they still run, even on a loaded machine, and it
/// leaves before the end (the clock must not blame anyone for its leaving).
const std::string kScenario = "crack-descent --set duration_s=8";

/// climbsim-test-outsider running on a domain, its stdout read line by line.
class Outsider {
 public:
  Outsider(int domain, const std::string& args, const fs::path& log) {
    const std::string command = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-test-outsider --domain " +
                                std::to_string(domain) + " " + args + " 2> " + log.string();
    pipe_ = ::popen(command.c_str(), "r");
  }
  ~Outsider() {
    if (pipe_ != nullptr) finish();
  }
  /// Reads lines until one equals `line` (true) or the outsider ends (false).
  bool awaitLine(const std::string& line) {
    char buffer[512];
    while (pipe_ != nullptr && std::fgets(buffer, sizeof buffer, pipe_) != nullptr) {
      std::string got(buffer);
      if (!got.empty() && got.back() == '\n') got.pop_back();
      lines_.push_back(got);
      if (got == line) return true;
    }
    return false;
  }
  /// Reads to the end; the outsider's exit code.
  int finish() {
    awaitLine("\x01 never");
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  bool said(const std::string& line) const {
    for (const auto& l : lines_) {
      if (l == line) return true;
    }
    return false;
  }
  std::string allLines() const {
    std::string all;
    for (const auto& l : lines_) all += l + "\n";
    return all;
  }

 private:
  FILE* pipe_ = nullptr;
  std::vector<std::string> lines_;
};

/// A free domain id for a run the test starts on purpose on a domain it chose.
int freeDomain() {
  climbsim::DomainLease lease(150, 199);
  return lease.id();  // released here: the launcher leases it again with --domain
}

std::string logOf(const RunResult& run, const std::string& process) {
  return readFile(run.dir / "logs" / (process + ".log"));
}

TEST(Security, AnOutsidersForgedSamplesAndAStaleStopChangeNothing) {
  const auto undisturbed = runScenario("security-undisturbed", kScenario);
  ASSERT_EQ(undisturbed.exit_code, 0) << undisturbed.output;

  const int domain = freeDomain();
  const fs::path outsider_log = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "security-outsider.log";
  fs::create_directories(outsider_log.parent_path());
  Outsider outsider(domain, "--stale-stop --attack-at-step 100", outsider_log);
  // A latched Stop of "an earlier run" is on the domain before any service of this run starts.
  ASSERT_TRUE(outsider.awaitLine("stale stop published")) << readFile(outsider_log);
  const auto attacked = runScenario("security-attacked", kScenario + " --domain " + std::to_string(domain));
  const int outsider_code = outsider.finish();

  ASSERT_EQ(outsider_code, 0) << outsider.allLines() << readFile(outsider_log);
  for (const char* attack : {"sent valves", "sent grant", "sent failed", "sent blame", "sent stop", "leaving"}) {
    EXPECT_TRUE(outsider.said(attack)) << attack << "\n" << outsider.allLines();
  }
  ASSERT_EQ(attacked.exit_code, 0) << attacked.output;
  EXPECT_TRUE(readFile(undisturbed.dir / "trace.csv") == readFile(attacked.dir / "trace.csv"))
      << "the outsider changed the trace";
  // Each forgery was seen and dropped where it was aimed, with the forging writer named.
  EXPECT_NE(logOf(attacked, "thermo").find("dropped a sample of 'controller/ValveCommand' from writer"),
            std::string::npos)
      << logOf(attacked, "thermo");
  EXPECT_NE(logOf(attacked, "clock").find("dropped a sample of 'clock/StepDone' from writer"), std::string::npos)
      << logOf(attacked, "clock");
  EXPECT_NE(logOf(attacked, "drive").find("dropped a sample of 'clock/Stop' from writer"), std::string::npos)
      << logOf(attacked, "drive");
  EXPECT_EQ(logOf(attacked, "clock").find("the outsider"), std::string::npos) << logOf(attacked, "clock");
}

/// A compose file of three test participants, paused at step 0 until resumed.
fs::path pausedCompose(const std::string& tag, const std::string& clock_extra) {
  const fs::path file = fs::path(CLIMBSIM_TEST_RUNS_DIR) / (tag + ".yaml");
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "name: " << tag << "\n"
                      << "clock: {step_ms: 5, steps: 400, start_paused: true, start_timeout_s: 60" << clock_extra
                      << "}\n"
                      << "services:\n"
                      << "  a: {command: [climbsim-test-participant, --reads, b]}\n"
                      << "  b: {command: [climbsim-test-participant, --reads, a], period: 2, offset: 1}\n";
  return file;
}

TEST(Security, APauseNobodyResumesEndsTheRunAfterMaxPauseWithItsReason) {
  const fs::path compose = pausedCompose("security-max-pause", ", max_pause_s: 2");
  const auto run = runScenario("security-max-pause", "-f " + compose.string());
  EXPECT_EQ(run.exit_code, 4) << run.output;
  EXPECT_NE(logOf(run, "clock").find("paused for 2 s and nobody resumed it (clock.max_pause_s); stopped before step 0"),
            std::string::npos)
      << logOf(run, "clock") << run.output;
}

TEST(Security, OnlyTheListedSendersControlTheClock) {
  // Paused at step 0: an outsider's STOP and PAUSE (claiming to be climbsim-clockctl) are
  // refused; climbsim-clockctl from this machine (the default clock.control) resumes it, and
  // the run completes.
  // max_pause_s: should the resume be refused, the run ends (exit 4) instead of hanging.
  const fs::path compose = pausedCompose("security-control", ", max_pause_s: 60");
  const int domain = freeDomain();
  const fs::path outsider_log = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "security-control-outsider.log";
  Outsider outsider(domain, "--control --attack-at-step 0 --valve-steps 0 --victim a", outsider_log);
  const std::string clockctl = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-clockctl --domain " + std::to_string(domain) + " --timeout-s 30";
  auto run = std::async(std::launch::async, [&] {
    return runScenario("security-control", "-f " + compose.string() + " --domain " + std::to_string(domain));
  });
  ASSERT_TRUE(outsider.awaitLine("sent control")) << outsider.allLines() << readFile(outsider_log);
  ASSERT_TRUE(outsider.awaitLine("leaving")) << outsider.allLines() << readFile(outsider_log);
  EXPECT_EQ(outsider.finish(), 0) << readFile(outsider_log);
  // The outsider's commands reached the clock (it acknowledged them) and changed nothing:
  // the resume of the real climbsim-clockctl is what lets the run go on.
  EXPECT_EQ(std::system((clockctl + " resume").c_str()), 0);
  const auto result = run.get();
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string clock_log = logOf(result, "clock");
  EXPECT_NE(clock_log.find("dropped a sample of 'clock/ClockControl' from writer"), std::string::npos) << clock_log;
  EXPECT_NE(clock_log.find("'outsider' is not among the senders the compose file's clock.control allows"),
            std::string::npos)
      << clock_log;
  EXPECT_NE(clock_log.find("control from 'climbsim-clockctl'"), std::string::npos) << clock_log;
}

}  // namespace
