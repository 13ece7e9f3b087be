#pragma once
/// @file
/// Integration-test harness: the real clock and real test participants as separate
/// processes on a domain of their own, and an in-process DDS observer that sees SimTime
/// and Stop and sends ClockControl, so that tests await events instead of sleeping.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "climbsim/topic_names.hpp"
#include "climbsim/dds_context.hpp"
#include "climbsim/domain_lease.hpp"
#include "climbsim/process.hpp"
#include "clockPubSubTypes.h"

namespace climbsim::testing {

#ifndef CLIMBSIM_BIN_DIR
#error "CLIMBSIM_BIN_DIR must point at the built executables"
#endif

using Clock = std::chrono::steady_clock;

/// Reads a whole file.
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream out;
  out << in.rdbuf();
  return out.str();
}

/// One test's processes, logs and domain.
class LockstepRun {
 public:
  /// `tag` names the run's directory under the build tree.
  explicit LockstepRun(const std::string& tag)
      : domain_(100, 199), dir_(std::filesystem::path(CLIMBSIM_TEST_RUNS_DIR) / tag) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }

  int domain() const { return domain_.id(); }
  /// The run id the clock is started with (--run-id) and every process gets (CLIMBSIM_RUN_ID).
  std::uint64_t runId() const { return 7000 + static_cast<std::uint64_t>(domain()); }
  const std::filesystem::path& dir() const { return dir_; }

  /// Starts `exe` (in the build's bin/) with `args` and --domain; output to <dir>/<name>.log.
  ChildProcess& start(const std::string& name, const std::string& exe, std::vector<std::string> args) {
    ProcessSpec spec;
    spec.argv.push_back(std::string(CLIMBSIM_BIN_DIR) + "/" + exe);
    spec.argv.insert(spec.argv.end(), args.begin(), args.end());
    spec.argv.push_back("--domain");
    spec.argv.push_back(std::to_string(domain()));
    spec.env["CLIMBSIM_RUN_ID"] = std::to_string(runId());  // as the launcher gives every process
    spec.output_file = (dir_ / (name + ".log")).string();
    std::filesystem::remove(spec.output_file);
    return processes_.emplace(name, ChildProcess(spec)).first->second;
  }

  /// The clock with this roster and extra options.
  ChildProcess& startClock(const std::string& roster, std::vector<std::string> args) {
    args.insert(args.begin(), {"--roster", roster, "--run-id", std::to_string(runId())});
    return start("clock", "climbsim-clock", args);
  }

  /// A test participant recording what it reads to <dir>/<name>.rec.
  ChildProcess& startParticipant(const std::string& name, int period, int offset, const std::string& reads,
                                 std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"--name",  name, "--period", std::to_string(period), "--offset",
                                     std::to_string(offset), "--record", (dir_ / (name + ".rec")).string()};
    if (!reads.empty()) {
      args.insert(args.end(), {"--reads", reads});
    }
    args.insert(args.end(), extra.begin(), extra.end());
    return start(name, "climbsim-test-participant", args);
  }

  ChildProcess& process(const std::string& name) { return processes_.at(name); }
  std::string log(const std::string& name) const { return readFile(dir_ / (name + ".log")); }
  std::string record(const std::string& name) const { return readFile(dir_ / (name + ".rec")); }

  /// Waits for every process to end; their exit codes by name (missing: still running).
  std::map<std::string, int> waitAll(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    std::map<std::string, int> codes;
    for (auto& [name, process] : processes_) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (auto code = process.waitFor(std::max(left, std::chrono::milliseconds(0)))) {
        codes[name] = *code;
      }
    }
    return codes;
  }

  /// Every log, for failure messages.
  std::string allLogs() const {
    std::string out;
    for (const auto& [name, process] : processes_) {
      out += "---- " + name + ".log\n" + log(name);
    }
    return out;
  }

 private:
  DomainLease domain_;
  std::filesystem::path dir_;
  std::map<std::string, ChildProcess> processes_;
};

/// An in-process observer on the run's domain: SimTime and Stop in, ClockControl out.
class Observer {
 public:
  explicit Observer(int domain) {
    DdsSettings settings;
    settings.domain_id = domain;
    settings.qos_file = CLIMBSIM_QOS_FILE;
    dds_ = std::make_unique<DdsContext>(settings, "test-observer");
    sim_time_ = std::make_unique<Reader<SimTimePubSubType>>(*dds_, topic::kSimTime, qos::kObserver, notifier_);
    stop_ = std::make_unique<Reader<StopPubSubType>>(*dds_, topic::kStop, qos::kLatched, notifier_);
    control_ = std::make_unique<Writer<ClockControlPubSubType>>(*dds_, topic::kClockControl, qos::kControl, notifier_);
  }

  /// Waits until `predicate` holds for a received SimTime; returns it and its arrival time.
  std::optional<std::pair<SimTime, Clock::time_point>> awaitSimTime(const std::function<bool(const SimTime&)>& predicate,
                                                                    std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (true) {
      const auto seen = notifier_.generation();
      for (auto& r : sim_time_->take()) {
        last_sim_time_ = r.data;
        if (predicate(r.data)) {
          return std::make_pair(r.data, Clock::now());
        }
      }
      pollStop();
      if (Clock::now() >= deadline || stop_msg_) {
        return std::nullopt;
      }
      notifier_.waitChanged(seen, deadline);
    }
  }

  /// Waits for the clock's Stop; returns it and its arrival time.
  std::optional<std::pair<Stop, Clock::time_point>> awaitStop(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!stop_msg_) {
      const auto seen = notifier_.generation();
      pollStop();
      if (stop_msg_ || Clock::now() >= deadline) {
        break;
      }
      notifier_.waitChanged(seen, deadline);
    }
    if (!stop_msg_) {
      return std::nullopt;
    }
    return std::make_pair(*stop_msg_, stop_at_);
  }

  /// Sends a ClockControl once the clock's reader is matched.
  bool send(ClockCommand command, std::uint32_t steps = 1, double rtf = 0.0) {
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (control_->matchedReaders() == 0) {
      const auto seen = notifier_.generation();
      if (control_->matchedReaders() > 0) break;
      if (!notifier_.waitChanged(seen, deadline)) return false;
    }
    ClockControl control;
    control.command(command);
    control.steps(steps);
    control.realtime_factor(rtf);
    control.sender("integration-test");
    control_->write(control);
    return true;
  }

 private:
  void pollStop() {
    for (auto& r : stop_->take()) {
      if (!stop_msg_) {
        stop_msg_ = r.data;
        stop_at_ = Clock::now();
      }
    }
  }

  Notifier notifier_;
  std::unique_ptr<DdsContext> dds_;
  std::unique_ptr<Reader<SimTimePubSubType>> sim_time_;
  std::unique_ptr<Reader<StopPubSubType>> stop_;
  std::unique_ptr<Writer<ClockControlPubSubType>> control_;
  std::optional<SimTime> last_sim_time_;
  std::optional<Stop> stop_msg_;
  Clock::time_point stop_at_{};
};

}  // namespace climbsim::testing
