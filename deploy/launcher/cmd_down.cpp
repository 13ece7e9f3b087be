/// `down`: stop a running composition, gracefully first.

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>

#include <spdlog/spdlog.h>

#include "climbsim/process.hpp"
#include "commands.hpp"
#include "file_lock.hpp"
#include "lock_wait.hpp"
#include "run_registry.hpp"
#include "run_state.hpp"
#include "launch_plan.hpp"
#include "security_material.hpp"

namespace climbsim::launcher {

namespace {
using namespace std::chrono_literals;
using std::chrono::steady_clock;

/// How long `down` waits for the supervisor after asking the clock to stop.
constexpr auto kStopWait = 10s;
/// How long it waits after SIGTERM, and after SIGKILL.
constexpr auto kSignalWait = 5s;

/// Asks the clock on `domain_id` to stop the run (climbsim-clockctl stop); true if it took it.
/// In a secured run (a security directory beside the trace or in the run directory) clockctl
/// loads its identity from there.
bool askClockToStop(const CommandContext& context, const RunState& state) {
  ProcessSpec spec;
  spec.argv = {context.build_dir + "/bin/climbsim-clockctl", "--domain", std::to_string(state.domain_id), "--timeout-s",
               "5", "stop"};
  for (const std::string& dir : {state.out_dir, state.run_dir}) {
    const std::filesystem::path security = std::filesystem::path(dir) / kSecurityDirName;
    if (!dir.empty() && std::filesystem::exists(security / kClockCtlName)) {
      spec.env = securityEnvironment(security.string(), kClockCtlName);
      break;
    }
  }
  spec.output_fd = STDERR_FILENO;
  try {
    ChildProcess clockctl(spec);
    const auto code = clockctl.waitFor(15s);  // clockctl gives up by itself after 2 x 5 s
    return code && *code == 0;
  } catch (const std::exception& e) {
    spdlog::warn("{}", e.what());
    return false;
  }
}

/// Sends `signal_number` to the supervisor's process group if it leads one (a detached
/// run), else to the supervisor alone (it passes the request on to its processes).
void signalSupervisor(const std::string& lock_file, bool detached, int signal_number) {
  const auto pid = FileLock::readOwner(lock_file);
  if (!pid || !FileLock::isHeld(lock_file)) {
    return;
  }
  spdlog::warn("sending {} to the supervisor{} (pid {})", signal_number == SIGKILL ? "SIGKILL" : "SIGTERM",
               detached ? " and its processes" : "", *pid);
  if (detached && ::getpgid(*pid) == *pid) {
    ::kill(-*pid, signal_number);
  } else {
    ::kill(*pid, signal_number);
  }
}
}  // namespace

namespace {
/// Stops one run; 0 when it is no longer running.
int stopRun(const CommandContext& context, const RunEntry& run) {
  const RunPaths& paths = run.paths;
  const std::string& name = run.name;
  if (!FileLock::isHeld(paths.lock_file)) {
    spdlog::info("'{}' is not running; nothing to stop", name);
    return 0;
  }
  std::optional<RunState> state;
  try {
    state = readRunState(paths.state_file);
  } catch (const std::exception& e) {
    spdlog::warn("{}", e.what());
  }
  const bool detached = state && state->detached;
  const bool clock_running = state && !state->processes.empty() && !state->processes.front().exit_code;
  if (clock_running) {
    spdlog::info("asking the clock of '{}' on DDS domain {} to stop the run", name, state->domain_id);
    if (!askClockToStop(context, *state)) {
      spdlog::warn("the clock did not take the stop request");
    }
  }
  if (!waitForLockRelease(paths.lock_file, steady_clock::now() + kStopWait)) {
    signalSupervisor(paths.lock_file, detached, SIGTERM);
    if (!waitForLockRelease(paths.lock_file, steady_clock::now() + kSignalWait)) {
      signalSupervisor(paths.lock_file, detached, SIGKILL);
      if (!waitForLockRelease(paths.lock_file, steady_clock::now() + kSignalWait)) {
        spdlog::error("could not stop '{}': its supervisor still holds {}", name, paths.lock_file);
        return 1;
      }
    }
  }
  std::optional<RunState> final_state;
  try {
    final_state = readRunState(paths.state_file);
  } catch (const std::exception&) {
  }
  if (final_state && final_state->exit_code) {
    spdlog::info("'{}' stopped (the run's exit code: {})", name, *final_state->exit_code);
  } else {
    spdlog::info("'{}' stopped", name);
  }
  return 0;
}
}  // namespace

int commandDown(const CommandContext& context, const std::string& name, bool all) {
  const std::string filter = context.compose_given ? context.compose_file : std::string();
  if (all) {
    int code = 0;
    for (const auto& run : listRuns(context.build_dir)) {
      if (!run.running || (!filter.empty() && (!run.state || run.state->compose_file != filter))) continue;
      code = std::max(code, stopRun(context, run));
    }
    return code;
  }
  const std::optional<RunEntry> run = selectRun(context.build_dir, name, filter, false);
  if (!run) {
    spdlog::info("no run is running; nothing to stop");
    return 0;
  }
  return stopRun(context, *run);
}

}  // namespace climbsim::launcher
