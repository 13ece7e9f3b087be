// Sweeps on a Ray cluster (`sweep --ray`, docs/deployment.md#sweeps-on-a-ray-cluster): a head on
// this machine and a worker node on the test host (the network namespace of `hosts up`), joined
// with `ray start --address` as a second machine is (`deploy/climbsim cluster up --test-host`).
// The variants come back as a local sweep's; a lost worker's variants run again elsewhere, once
// each; a node without the build is named in one line.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "launcher_run.hpp"

namespace {

using namespace climbsim::system_test;
using SteadyClock = std::chrono::steady_clock;

/// The test cluster's port (a user's cluster runs on 6379).
constexpr int kPort = 6571;
const std::string kAddress = "10.77.0.1:" + std::to_string(kPort);

/// 8 set-points of 2 s runs of crack-descent.
const std::string kSweep =
    "crack-descent --set duration_s=2 --set controller.downforce_n=600,800,1000,1200,1400,1600,1800,2000";

std::string climbsim(const std::string& args) {
  return "CLIMBSIM_BUILD_DIR=" CLIMBSIM_BUILD_DIR " " CLIMBSIM_ROOT "/deploy/climbsim " + args;
}

/// sweep.csv without its wall_s column (the one figure measured, not computed).
std::string withoutWallTime(const std::string& csv) {
  std::istringstream lines(csv);
  std::string out;
  std::size_t column = std::string::npos;
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::size_t at = 0;
    for (std::size_t comma; (comma = line.find(',', at)) != std::string::npos && line[at] != '"'; at = comma + 1) {
      cells.push_back(line.substr(at, comma - at));
    }
    if (column == std::string::npos) {
      for (std::size_t i = 0; i < cells.size(); ++i) column = cells[i] == "wall_s" ? i : column;
    }
    std::size_t start = 0;
    for (std::size_t i = 0; i < column; ++i) start = line.find(',', start) + 1;
    out += line.substr(0, start) + line.substr(line.find(',', start) + 1) + "\n";
  }
  return out;
}

/// The variant directories of a sweep, in order.
std::vector<std::string> variantsOf(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory()) names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// The local sweep every Ray sweep is compared with (`-j 2`), run once.
const RunResult& localSweep() {
  static const RunResult local = runTool("climbsim-sweep", "ray-local", kSweep + " -j 2");
  return local;
}

/// Expects the Ray sweep in `dir` to have given what the local one gave: sweep.csv but wall_s,
/// every variant's trace.csv, the overlay plots, byte for byte.
void expectSameAsLocal(const fs::path& dir) {
  const auto& local = localSweep();
  ASSERT_EQ(local.exit_code, 0) << local.output;
  EXPECT_EQ(withoutWallTime(readFile(dir / "sweep.csv")), withoutWallTime(readFile(local.dir / "sweep.csv")));
  EXPECT_EQ(lineCount(readFile(dir / "sweep.csv")), 9u) << "a header and every variant once";
  const auto names = variantsOf(local.dir);
  ASSERT_EQ(names.size(), 8u);
  EXPECT_EQ(variantsOf(dir), names);
  for (const auto& name : names) {
    EXPECT_TRUE(readFile(dir / name / "trace.csv") == readFile(local.dir / name / "trace.csv")) << name;
    EXPECT_TRUE(fs::exists(dir / (name + ".log"))) << name;
  }
  for (const char* plot : {"downforce.png", "pf.png"}) {
    EXPECT_TRUE(readFile(dir / plot) == readFile(local.dir / plot)) << plot;
  }
}

class RaySweep : public ::testing::Test {
 protected:
  void SetUp() override {
    if (::geteuid() != 0) GTEST_SKIP() << "the test host is a network namespace: root only (CI runs as root)";
    // A cluster an interrupted test left on the test port goes first.
    std::system(climbsim("cluster down --port " + std::to_string(kPort) + " > /dev/null 2>&1").c_str());
    ASSERT_EQ(std::system(climbsim("cluster up --port " + std::to_string(kPort) + " --cpus " + cpus_ +
                                   " --test-host > /dev/null").c_str()),
              0)
        << "`deploy/climbsim cluster up --test-host` failed";
  }
  void TearDown() override {
    if (::geteuid() == 0) std::system(climbsim("cluster down --port " + std::to_string(kPort)).c_str());
  }
  std::string cpus_ = "1";  ///< CPUs of each node
};

TEST_F(RaySweep, VariantsOnAHeadAndAWorkerOnTheTestHostGiveTheLocalSweepsFiles) {
  // auto: the cluster `cluster up` started last, this test's.
  const auto ray = runTool("climbsim-sweep", "ray-sweep", kSweep + " --ray auto");
  ASSERT_EQ(ray.exit_code, 0) << ray.output;
  expectSameAsLocal(ray.dir);
  // Both nodes ran variants (one CPU each: two at a time).
  EXPECT_NE(ray.output.find("variants by node: 10.77.0.1"), std::string::npos) << ray.output;
  EXPECT_NE(ray.output.find(", 10.77.0.2 ("), std::string::npos) << ray.output;
  EXPECT_NE(ray.output.find("8/8 done (0 fell, 0 slid, 0 failed)"), std::string::npos) << ray.output;
}

/// A climbsim-solo process in the test host's network namespace, or 0.
pid_t soloOnTestHost() {
  FILE* pids = ::popen("ip netns pids climbsim-b", "r");
  if (pids == nullptr) return 0;
  pid_t found = 0;
  for (int pid; std::fscanf(pids, "%d", &pid) == 1;) {
    if (readFile("/proc/" + std::to_string(pid) + "/comm") == "climbsim-solo\n") found = pid;
  }
  ::pclose(pids);
  return found;
}

TEST_F(RaySweep, KillingTheWorkersRayProcessesMidSweepRunsItsVariantsAgainOnTheHeadOnce) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "ray-killed";
  fs::remove_all(dir);
  const std::string log = dir.string() + ".log";
  const pid_t sweep = ::fork();
  ASSERT_GE(sweep, 0);
  if (sweep == 0) {
    const std::string command =
        std::string(CLIMBSIM_BIN_DIR) + "/climbsim-sweep " + kSweep + " --ray " + kAddress + " --out " + dir.string();
    ::execl("/bin/sh", "sh", "-c", (command + " > " + log + " 2>&1").c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Polling the test host's processes: no event to await from outside the cluster.
  const auto deadline = SteadyClock::now() + std::chrono::seconds(120);
  while (soloOnTestHost() == 0 && SteadyClock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_NE(soloOnTestHost(), 0) << "no variant ran on the worker\n" << readFile(log);
  // Every Ray process of the worker node at once, as when its machine dies.
  const fs::path groups = fs::path(CLIMBSIM_BUILD_DIR) / "ray" / std::to_string(kPort) / "test-host.pgids";
  std::istringstream pgids(readFile(groups));
  int killed = 0;
  for (pid_t pgid; pgids >> pgid;) killed += ::kill(-pgid, SIGKILL) == 0 ? 1 : 0;
  ASSERT_GT(killed, 0) << readFile(groups);
  int status = 0;
  ASSERT_EQ(::waitpid(sweep, &status, 0), sweep);
  const std::string output = readFile(log);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << output;
  // The loss is told: by the driver once Ray's health check declares the node dead, or sooner
  // by Ray's own retry line for a task whose node died (a short sweep may end before the first).
  EXPECT_TRUE(output.find("node 10.77.0.2 left the cluster") != std::string::npos ||
              (output.find("will be retried") != std::string::npos && output.find("10.77.0.2") != std::string::npos))
      << output;
  expectSameAsLocal(dir);
}

class RaySweepWithoutTheBuild : public RaySweep {
 protected:
  RaySweepWithoutTheBuild() { cpus_ = "0"; }  // the head and the test host's good worker run nothing
  void TearDown() override {
    if (::geteuid() != 0) return;
    // Ray's processes of this worker (their arguments name its temp dir), until none is left: a
    // raylet that is still starting may spawn another (its log monitor) after a first pass.
    // /bin/kill: the shell of std::system (dash) has a builtin kill that takes no "-- -PGID".
    std::system(("for pass in $(seq 50); do gs=$(ps -eo pgid=,args= | grep -F -- " + temp_ +
                 " | grep -v grep | awk '{print $1}' | sort -u); [ -z \"$gs\" ] && break; "
                 "for g in $gs; do /bin/kill -KILL -- -$g; done; sleep 0.1; done")
                    .c_str());
    fs::remove_all(temp_);
    RaySweep::TearDown();
  }
  const std::string temp_ = "/tmp/climbsim-ray-" + std::to_string(kPort) + "-nobuild";
};

TEST_F(RaySweepWithoutTheBuild, ANodeWithoutTheBuildIsNamedInOneLineAndTheSweepEndsNonZero) {
  // A worker on the test host that sees an empty build/bin (its own mount namespace): where a
  // machine without the checkout's build would join.
  const std::string ray = std::string(CLIMBSIM_BUILD_DIR) + "/venv/bin/ray";
  const std::string worker =
      "ip netns exec climbsim-b unshare -m sh -c 'mount -t tmpfs tmpfs " CLIMBSIM_BUILD_DIR "/bin && exec setsid " +
      ray + " start --address " + kAddress + " --node-ip-address 10.77.0.2 --num-cpus 1 --temp-dir " + temp_ +
      " --disable-usage-stats --dashboard-agent-listen-port " + std::to_string(kPort + 4) +
      " --metrics-export-port " + std::to_string(kPort + 5) + " --object-store-memory 300000000' > /dev/null 2>&1";
  ASSERT_EQ(std::system(worker.c_str()), 0) << worker;
  const auto started = SteadyClock::now();
  const auto r = runTool("climbsim-sweep", "ray-no-build", "crack-descent --set duration_s=1 --set "
                                                           "controller.downforce_n=900,1500 --ray " + kAddress);
  EXPECT_LT(std::chrono::duration<double>(SteadyClock::now() - started).count(), 120.0) << "nothing hangs";
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const std::string line = "sweep: node 10.77.0.2 (";
  const auto at = r.output.find(line);
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(line, at + 1), std::string::npos) << "one line:\n" << r.output;
  EXPECT_NE(r.output.find("has no " CLIMBSIM_BUILD_DIR "/bin/climbsim-solo: every node needs the checkout and build"),
            std::string::npos)
      << r.output;
}

TEST(RaySweepAddress, NoClusterAtTheAddressIsOneLineAndExitNonZero) {
  const auto r = runTool("climbsim-sweep", "ray-nowhere", "crack-descent --set controller.downforce_n=900 --ray 127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--ray 127.0.0.1:1: no Ray cluster answers at 127.0.0.1:1"), std::string::npos) << r.output;
}

}  // namespace
