// A run tells the truth about faults of its own processes: a recorder that is
// killed still leaves a summary.json (the launcher's), and a service that is stopped (SIGSTOP)
// is named with the right words and the run ends within about 3 s.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>

#include "launcher_run.hpp"

namespace climbsim::system_test {
namespace {

using SteadyClock = std::chrono::steady_clock;

/// A launcher run in the background (`run crack-descent --name NAME --out DIR ARGS`).
class BackgroundRun {
 public:
  BackgroundRun(const std::string& name, const std::vector<std::string>& extra) : name_(name) {
    dir_ = fs::path(CLIMBSIM_TEST_RUNS_DIR) / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_.parent_path());
    log_ = dir_.string() + ".log";
    std::vector<std::string> args = {std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose", "--root", CLIMBSIM_ROOT,
                                     "--build", CLIMBSIM_BUILD_DIR, "run", "crack-descent", "--name", name,
                                     "--out", dir_.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    pid_ = ::fork();
    if (pid_ == 0) {
      const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  ~BackgroundRun() {
    if (pid_ > 0 && !status_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  /// Waits (polling the file: no event to await) until trace.csv has `rows` rows.
  bool awaitRows(std::size_t rows) const {
    const auto deadline = SteadyClock::now() + std::chrono::seconds(120);
    while (SteadyClock::now() < deadline) {
      const std::string trace = fs::exists(dir_ / "trace.csv") ? readFile(dir_ / "trace.csv") : std::string();
      if (static_cast<std::size_t>(std::count(trace.begin(), trace.end(), '\n')) > rows) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  /// Waits (polling the launcher's state.json: no event to await) until `process` has exited;
  /// false if it has not within 120 s.
  bool awaitExited(const std::string& process) const {
    const auto deadline = SteadyClock::now() + std::chrono::seconds(120);
    const fs::path file = fs::path(CLIMBSIM_BUILD_DIR) / "run" / name_ / "state.json";
    while (SteadyClock::now() < deadline) {
      // A state.json read while the launcher rewrites it may not parse: read it again.
      const auto state = nlohmann::json::parse(fs::exists(file) ? readFile(file) : std::string(), nullptr, false);
      if (!state.is_discarded() && state.contains("processes")) {
        for (const auto& p : state.at("processes")) {
          if (p.value("name", "") == process && p.contains("exit_code") && !p.at("exit_code").is_null()) return true;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  /// The pid of a process of the run, from the launcher's state.json.
  pid_t pidOf(const std::string& process) const {
    const auto state = nlohmann::json::parse(readFile(fs::path(CLIMBSIM_BUILD_DIR) / "run" / name_ / "state.json"));
    for (const auto& p : state.at("processes")) {
      if (p.at("name") == process) return p.at("pid").get<pid_t>();
    }
    return -1;
  }

  /// The launcher's exit code (waits for it).
  int exitCode() {
    if (!status_) {
      int status = 0;
      ::waitpid(pid_, &status, 0);
      status_ = status;
    }
    return WIFEXITED(*status_) ? WEXITSTATUS(*status_) : -1;
  }

  std::string log() const { return readFile(log_); }
  const fs::path& dir() const { return dir_; }

 private:
  std::string name_;
  fs::path dir_;
  std::string log_;
  pid_t pid_ = -1;
  std::optional<int> status_;
};

TEST(RunFaults, AKilledRecorderStillLeavesASummaryFromTheRowsItWrote) {
  BackgroundRun run("system-recorder-killed", {"--set", "duration_s=30"});
  ASSERT_TRUE(run.awaitRows(200)) << run.log();
  const pid_t recorder = run.pidOf("recorder");
  ASSERT_GT(recorder, 0);
  ASSERT_EQ(::kill(recorder, SIGKILL), 0);
  const int code = run.exitCode();
  EXPECT_NE(code, 0) << run.log();
  const auto summary = nlohmann::json::parse(readFile(run.dir() / "summary.json"), nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << run.log();
  EXPECT_EQ(summary["written_by"], "launcher");
  EXPECT_EQ(summary["outcome"], "failed");
  EXPECT_EQ(summary["exit_code"], code);
  EXPECT_EQ(summary["completed"], false);
  EXPECT_EQ(summary["culprit"], "recorder");
  // Nothing computed is lost: the summary counts every complete row trace.csv kept.
  const std::string trace = readFile(run.dir() / "trace.csv");
  std::size_t rows = static_cast<std::size_t>(std::count(trace.begin(), trace.end(), '\n')) - 1;
  EXPECT_GE(summary["steps"].get<std::size_t>(), 200u);
  EXPECT_LE(summary["steps"].get<std::size_t>(), rows);
  EXPECT_GE(summary["steps"].get<std::size_t>() + 1, rows);
}

TEST(RunFaults, AStoppedServiceIsNamedAsStoppedAndTheRunEndsWithinThreeSeconds) {
  BackgroundRun run("system-drive-stopped", {"--set", "duration_s=60"});
  ASSERT_TRUE(run.awaitRows(200)) << run.log();
  const pid_t drive = run.pidOf("drive");
  ASSERT_GT(drive, 0);
  const auto stopped_at = SteadyClock::now();
  ASSERT_EQ(::kill(drive, SIGSTOP), 0);
  // The run ends when the clock does; what the launcher does after it (stopping the others,
  // the plots: seconds on a loaded machine) is not part of it.
  ASSERT_TRUE(run.awaitExited("clock")) << run.log();
  const double took_s = std::chrono::duration<double>(SteadyClock::now() - stopped_at).count();
  const int code = run.exitCode();
  const std::string log = run.log();
  EXPECT_EQ(code, 1) << log;
  EXPECT_LT(took_s, 3.5) << log;  // "within 3 s", plus this machine's load
  EXPECT_NE(log.find("service 'drive' (pid " + std::to_string(drive) + ") is stopped (SIGSTOP"), std::string::npos)
      << log;
  const auto summary = nlohmann::json::parse(readFile(run.dir() / "summary.json"), nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << log;
  EXPECT_EQ(summary["outcome"], "failed");
  EXPECT_EQ(summary["culprit"], "drive") << summary.dump();
  EXPECT_EQ(summary["exit_code"], code);
  // The clock's own words: the process is stopped (it still existed when the clock saw it go
  // silent), not "left the domain"; and the launcher's last line says it too.
  const std::string reason = summary["reason"].get<std::string>();
  EXPECT_NE(reason.find("its process " + std::to_string(drive) + " is stopped (SIGSTOP"), std::string::npos) << reason;
  EXPECT_EQ(reason.find("left the domain"), std::string::npos) << reason;
  const auto last_line = log.substr(log.rfind('\n', log.size() - 2) + 1);
  EXPECT_NE(last_line.find("service 'drive' (pid " + std::to_string(drive) + ") was stopped (SIGSTOP"),
            std::string::npos)
      << last_line;
}

/// A process starved of CPU as on a loaded machine: moved into a cgroup (v1 cpu controller) with
/// 1 ms of CPU per second until the destructor, runnable all the while (state R or S, never T).
class CpuStarvation {
 public:
  static bool available() { return ::access("/sys/fs/cgroup/cpu/cgroup.procs", W_OK) == 0; }
  explicit CpuStarvation(pid_t pid) : dir_("/sys/fs/cgroup/cpu/climbsim-starved-" + std::to_string(::getpid())) {
    fs::create_directories(dir_);
    std::ofstream(dir_ / "cpu.cfs_period_us") << 1000000;
    std::ofstream(dir_ / "cpu.cfs_quota_us") << 1000;
    std::ofstream(dir_ / "cgroup.procs") << pid;  // every thread of the process
  }
  ~CpuStarvation() {
    std::ofstream(dir_ / "cpu.cfs_quota_us") << -1;
    std::istringstream pids(readFile(dir_ / "cgroup.procs"));
    for (std::string pid; std::getline(pids, pid);) std::ofstream("/sys/fs/cgroup/cpu/cgroup.procs") << pid;
    fs::remove(dir_);
  }

 private:
  fs::path dir_;
};

TEST(RunFaults, AServiceStarvedOfCpuForSecondsIsNoFailure) {
  // A loaded machine (a sweep of distributed runs at twice the cores, each loading its scene)
  // gives a service no CPU for seconds. Its process runs: the clock must not count it as
  // vanished (with a 1 s lease it did: "participant 'drive' vanished (DDS dropped it; its
  // process ... exists and runs but sends nothing)"). Paced at real time, so that the run is
  // still under way while the drive starves.
  if (!CpuStarvation::available()) GTEST_SKIP() << "needs the cgroup v1 cpu controller, writable (root)";
  BackgroundRun run("system-drive-starved", {"--set", "duration_s=5", "--rtf", "1"});
  ASSERT_TRUE(run.awaitRows(100)) << run.log();
  const pid_t drive = run.pidOf("drive");
  ASSERT_GT(drive, 0) << run.log();
  {
    CpuStarvation starved(drive);
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));  // the starvation itself, not a synchronisation
  }
  const int code = run.exitCode();
  const std::string log = run.log();
  EXPECT_EQ(code, 0) << log;
  EXPECT_EQ(log.find("vanished"), std::string::npos) << log;
  EXPECT_EQ(completeRows(run.dir() / "trace.csv"), 1000u) << log;
}

}  // namespace
}  // namespace climbsim::system_test
