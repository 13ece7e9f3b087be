// The closed loop across two hosts: deploy/compose.two-hosts.yaml puts the sealing shards on
// a second host, a network namespace joined to this one by a veth pair (`deploy/climbsim hosts
// up`), so DDS traffic really crosses a network link (Fast DDS uses shared memory only
// between processes it finds on the same host, which it tells by their network interfaces).

#include <gtest/gtest.h>

#include "launcher_run.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace climbsim::system_test;

const char* const kNamespace = "climbsim-b";
const char* const kLink = "csim-b-here";  // this side of the veth pair

/// Bytes sent and received on this side of the veth pair.
std::uint64_t linkBytes() {
  const fs::path stats = fs::path("/sys/class/net") / kLink / "statistics";
  return std::stoull(readFile(stats / "rx_bytes")) + std::stoull(readFile(stats / "tx_bytes"));
}

class TwoHosts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (::geteuid() != 0) {
      skip_reason_ = "network namespaces need root; run as root (CI does)";
      return;
    }
    const std::string up = std::string(CLIMBSIM_ROOT) + "/deploy/climbsim hosts up";
    setup_ok_ = std::system(up.c_str()) == 0;
  }
  void SetUp() override {
    if (!skip_reason_.empty()) GTEST_SKIP() << skip_reason_;
    ASSERT_TRUE(setup_ok_) << "`deploy/climbsim hosts up` failed: the second host could not be made";
  }

  static inline std::string skip_reason_;
  static inline bool setup_ok_ = false;
};

TEST_F(TwoHosts, SealingOnTheSecondHostGivesTheAllLocalTraceBitForBit) {
  const std::string scenario = "crack-descent --set duration_s=5";
  const auto local = runScenario("two-hosts-reference", scenario + " --window-steps 1");
  ASSERT_EQ(local.exit_code, 0) << local.output;

  const std::uint64_t bytes_before = linkBytes();
  const auto spread = runScenario("two-hosts-spread", scenario + " -f " + std::string(CLIMBSIM_ROOT) +
                                                   "/deploy/compose.two-hosts.yaml");
  ASSERT_EQ(spread.exit_code, 0) << spread.output;
  const std::uint64_t crossed = linkBytes() - bytes_before;

  // Each sealing shard reads every depth image (64x64 floats, 16 KiB, at 50 Hz) across the link.
  EXPECT_GT(crossed, 2u * 250u * 16u * 1024u) << "the sealing shards' inputs did not cross the veth link";
  EXPECT_EQ(completeRows(spread.dir / "trace.csv"), 1000u);
  EXPECT_TRUE(readFile(local.dir / "trace.csv") == readFile(spread.dir / "trace.csv"))
      << "the trace with the sealing shards on the second host differs from the all-local one";
  // The shards ran inside the namespace: their log says which host they announced.
  EXPECT_TRUE(fs::exists(spread.dir / "logs" / "sealing-0.log"));
  EXPECT_TRUE(fs::exists(spread.dir / "logs" / "sealing-1.log"));
}

TEST_F(TwoHosts, HiresLeakageWithItsRenderersOnTheSecondHostGivesTheAllLocalTraceAndNoImageCrossesTheLink) {
  // deploy/compose.hires-two-hosts.yaml: 2 depth renderers (--tile) and 2 sealing shards on
  // the second host; the reference is the default composition (1 renderer, 1 shard) here.
  const std::string scenario = "crack-descent-hires --set duration_s=1.5";
  const auto local = runScenario("hires-reference", scenario);
  ASSERT_EQ(local.exit_code, 0) << local.output;

  const std::uint64_t bytes_before = linkBytes();
  const auto spread = runScenario("hires-spread", scenario + " -f " + std::string(CLIMBSIM_ROOT) +
                                                    "/deploy/compose.hires-two-hosts.yaml");
  ASSERT_EQ(spread.exit_code, 0) << spread.output;
  const std::uint64_t crossed = linkBytes() - bytes_before;
  const std::size_t steps = completeRows(spread.dir / "trace.csv");
  EXPECT_EQ(steps, 300u);
  EXPECT_TRUE(readFile(local.dir / "trace.csv") == readFile(spread.dir / "trace.csv"))
      << "the hires trace with renderers and shards on the second host differs from the all-local one";
  // A shard reading whole images across the link would move one 4 MiB image per frame (every
  // 2 steps) per shard; with renderers next to the shards only poses, leakage, the clock's
  // messages and discovery cross it (including the start-up, which dominates a short run).
  const double per_step = static_cast<double>(crossed) / static_cast<double>(steps);
  std::printf("two hosts, hires: %llu bytes crossed the link in %zu steps: %.0f bytes per step\n",
              static_cast<unsigned long long>(crossed), steps, per_step);
  RecordProperty("bytes_per_step", std::to_string(per_step));
  EXPECT_LT(per_step, 0.05 * 4.0 * 1024 * 1024) << "depth images crossed the link";
  EXPECT_TRUE(fs::exists(spread.dir / "logs" / "scene-1.log"));
  EXPECT_TRUE(fs::exists(spread.dir / "logs" / "sealing-1.log"));
}

TEST_F(TwoHosts, KillingTheSecondHostStopsTheRunNamingItAndKeepsTheTrace) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "two-hosts-killed";
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  const std::string log = dir.string() + ".log";
  const std::string command = launcherCommand("crack-descent --set duration_s=60 -f " + std::string(CLIMBSIM_ROOT) +
                                           "/deploy/compose.two-hosts.yaml",
                                       dir) +
                              " > " + log + " 2>&1";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Await 1 s of simulated time in the trace (the recorder flushes every row).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (completeRows(dir / "trace.csv") < 200 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::size_t rows_before_kill = completeRows(dir / "trace.csv");
  ASSERT_GE(rows_before_kill, 200u) << readFile(log);

  // Every process of the second host dies at once, as when the machine goes away.
  const std::string kill = std::string("ip netns pids ") + kNamespace + " | xargs -r kill -KILL";
  ASSERT_EQ(std::system(kill.c_str()), 0);

  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string output = readFile(log);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_NE(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(output.find("service 'sealing-0' exited with code 137"), std::string::npos) << output;
  EXPECT_NE(output.find("service 'sealing-1' exited with code 137"), std::string::npos) << output;

  bool all_complete = false;
  const std::size_t rows = completeRows(dir / "trace.csv", &all_complete);
  EXPECT_GE(rows, rows_before_kill) << "rows written before the failure were lost";
  EXPECT_LT(rows, 12000u) << "the run went on to its end without the sealing shards";
  EXPECT_TRUE(all_complete) << "the trace ends in a half-written row";
  const std::string summary = readFile(dir / "summary.json");
  EXPECT_NE(summary.find("\"completed\": false"), std::string::npos) << summary;
}

/// A copy of deploy/<file> named `name` in the test runs directory, its scenario path made
/// absolute and each (from, to) replaced once; an empty path (and a test failure) if a `from`
/// is not in the file.
fs::path composeCopy(const std::string& file, const std::string& name,
                     const std::vector<std::pair<std::string, std::string>>& replacements) {
  std::string compose = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / file);
  std::vector<std::pair<std::string, std::string>> all = {
      {"scenario: scenarios/", "scenario: " + std::string(CLIMBSIM_ROOT) + "/deploy/scenarios/"}};
  all.insert(all.end(), replacements.begin(), replacements.end());
  const auto name_at = compose.find("\nname: ");
  if (name_at == std::string::npos) {
    ADD_FAILURE() << file << " has no name:";
    return {};
  }
  compose.replace(name_at + 7, compose.find('\n', name_at + 1) - (name_at + 7), name);
  for (const auto& [from, to] : all) {
    const auto at = compose.find(from);
    if (at == std::string::npos) {
      ADD_FAILURE() << "'" << from << "' is not in " << file;
      return {};
    }
    compose.replace(at, from.size(), to);
  }
  const fs::path copy = fs::path(CLIMBSIM_TEST_RUNS_DIR) / ("compose." + name + ".yaml");
  fs::create_directories(copy.parent_path());
  std::ofstream(copy) << compose;
  return copy;
}

/// An sshd inside the second host's namespace (10.77.0.2:22) that lets in one key, and an
/// ssh client configuration that uses it: the ssh kind of host, for real.
class SshdOnTheSecondHost {
 public:
  explicit SshdOnTheSecondHost(const fs::path& dir) : dir_(dir) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::create_directories("/run/sshd");  // sshd's privilege separation directory
    const std::string keygen = "ssh-keygen -q -t ed25519 -N '' -f ";
    ok_ = std::system((keygen + (dir_ / "host_key").string()).c_str()) == 0 &&
          std::system((keygen + (dir_ / "client_key").string()).c_str()) == 0;
    fs::copy_file(dir_ / "client_key.pub", dir_ / "authorized_keys");
    std::ofstream(dir_ / "sshd_config") << "ListenAddress 10.77.0.2\nPort 22\nHostKey " << (dir_ / "host_key").string()
                                        << "\nAuthorizedKeysFile " << (dir_ / "authorized_keys").string()
                                        << "\nPermitRootLogin prohibit-password\nPasswordAuthentication no\n"
                                           "KbdInteractiveAuthentication no\nUsePAM no\nStrictModes no\nPidFile "
                                        << (dir_ / "sshd.pid").string() << "\n";
    std::ofstream(dir_ / "ssh_config") << "Host 10.77.0.2\n  IdentityFile " << (dir_ / "client_key").string()
                                       << "\n  StrictHostKeyChecking no\n  UserKnownHostsFile /dev/null\n"
                                          "  ConnectTimeout 5\n";
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execlp("ip", "ip", "netns", "exec", kNamespace, "/usr/sbin/sshd", "-D", "-e", "-f",
               (dir_ / "sshd_config").c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Await a login (sshd listens within a fraction of a second; each try is a real login).
    const std::string probe = "ssh -F " + sshConfig() + " -o BatchMode=yes root@10.77.0.2 true 2>/dev/null";
    for (int attempt = 0; ok_ && attempt < 100; ++attempt) {
      if (std::system(probe.c_str()) == 0) {
        ready_ = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  ~SshdOnTheSecondHost() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  bool ready() const { return ready_; }
  std::string sshConfig() const { return (dir_ / "ssh_config").string(); }

 private:
  fs::path dir_;
  pid_t pid_ = -1;
  bool ok_ = false;
  bool ready_ = false;
};

TEST_F(TwoHosts, SealingOverSshGivesTheAllLocalTraceBitForBit) {
  const fs::path runs(CLIMBSIM_TEST_RUNS_DIR);
  SshdOnTheSecondHost sshd(runs / "two-hosts-sshd");
  ASSERT_TRUE(sshd.ready()) << "no ssh login to root@10.77.0.2 inside " << kNamespace;

  // deploy/compose.two-hosts.yaml with the second host reached over ssh instead of `ip netns`.
  const fs::path compose_file = composeCopy(
      "compose.two-hosts.yaml", "climbsim-two-hosts-ssh",
      {{"second: {netns: climbsim-b, address: 10.77.0.2}",
        "second: {ssh: root@10.77.0.2, address: 10.77.0.2, ssh_options: [-F, " + sshd.sshConfig() + "]}"}});
  ASSERT_FALSE(compose_file.empty());

  const std::string scenario = "crack-descent --set duration_s=3";
  const auto local = runScenario("two-hosts-ssh-reference", scenario + " --window-steps 1");
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const auto spread = runScenario("two-hosts-ssh", scenario + " -f " + compose_file.string());
  ASSERT_EQ(spread.exit_code, 0) << spread.output;
  EXPECT_EQ(completeRows(spread.dir / "trace.csv"), 600u);
  EXPECT_TRUE(readFile(local.dir / "trace.csv") == readFile(spread.dir / "trace.csv"))
      << "the trace with the sealing shards reached over ssh differs from the all-local one";
  EXPECT_NE(readFile(spread.dir / "logs" / "sealing-1.log").find("run completed"), std::string::npos)
      << readFile(spread.dir / "logs" / "sealing-1.log");
}

TEST_F(TwoHosts, SecuredOverSshTheSecondHostGetsItsOwnKeysAndTheTraceIsTheSame) {
  const fs::path runs(CLIMBSIM_TEST_RUNS_DIR);
  SshdOnTheSecondHost sshd(runs / "two-hosts-sshd-secured");
  ASSERT_TRUE(sshd.ready()) << "no ssh login to root@10.77.0.2 inside " << kNamespace;
  // security: on: the launcher copies the CA certificate, the governance and the
  // shards' own identities to the ssh host, at the same path.
  const fs::path compose_file = composeCopy(
      "compose.two-hosts.yaml", "climbsim-two-hosts-ssh-secured",
      {{"second: {netns: climbsim-b, address: 10.77.0.2}",
        "second: {ssh: root@10.77.0.2, address: 10.77.0.2, ssh_options: [-F, " + sshd.sshConfig() + "]}"},
       {"\nhosts:", "\nsecurity: on\nhosts:"}});
  ASSERT_FALSE(compose_file.empty());

  const std::string scenario = "crack-descent --set duration_s=2";
  const auto local = runScenario("two-hosts-ssh-secured-reference", scenario);
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const auto spread = runScenario("two-hosts-ssh-secured", scenario + " -f " + compose_file.string());
  ASSERT_EQ(spread.exit_code, 0) << spread.output;
  EXPECT_EQ(completeRows(spread.dir / "trace.csv"), 400u);
  EXPECT_TRUE(readFile(local.dir / "trace.csv") == readFile(spread.dir / "trace.csv"))
      << "the secured trace with the sealing shards reached over ssh differs from the all-local one";
  const fs::path security = spread.dir / "security";
  EXPECT_TRUE(fs::exists(security / "sealing-0" / "identity.key.pem"));
  EXPECT_TRUE(fs::exists(security / "ca.cert.pem"));
  // (The namespace shares this machine's files: which files the copy brought cannot be told
  // apart here; the launcher says what it sent, the two shards' identities only.)
  EXPECT_NE(spread.output.find("copied the CA certificate, the governance and 2 identities to host 'second'"),
            std::string::npos)
      << spread.output;
}

TEST_F(TwoHosts, APythonControllerOnTheSecondHostGivesTheCppTrace) {
#ifndef CLIMBSIM_HAVE_PYTHON
  GTEST_SKIP() << "built with CLIMBSIM_PYTHON=OFF: no Python clients";
#endif
  // deploy/compose.python-controller.yaml with the controller (Cyclone DDS) on the second host.
  const fs::path compose_file = composeCopy(
      "compose.python-controller.yaml", "climbsim-python-second-host",
      {{"services:", "hosts:\n  local: {address: 10.77.0.1}\n  second: {netns: climbsim-b, address: 10.77.0.2}\nservices:"},
       {"[climbsim-py-controller, --scenario, \"${scenario}\"]}",
        "[climbsim-py-controller, --scenario, \"${scenario}\"], host: second}"}});
  ASSERT_FALSE(compose_file.empty());

  const std::string scenario = "crack-descent --set duration_s=3";
  const auto cpp = runScenario("python-second-host-reference", scenario + " --window-steps 1");
  ASSERT_EQ(cpp.exit_code, 0) << cpp.output;
  const auto python = runScenario("python-second-host", scenario + " -f " + compose_file.string());
  ASSERT_EQ(python.exit_code, 0) << python.output;
  EXPECT_EQ(completeRows(python.dir / "trace.csv"), 600u);
  // The Python port computes what the C++ controller does, in the same order: the same bytes.
  EXPECT_TRUE(readFile(cpp.dir / "trace.csv") == readFile(python.dir / "trace.csv"))
      << "the Python controller on the second host gave another trace than the C++ controller here";
}

}  // namespace
