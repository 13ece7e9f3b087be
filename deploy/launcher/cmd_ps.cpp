/// `ps`: the processes of a composition and what became of them.

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "compose_file.hpp"
#include "file_lock.hpp"
#include "run_state.hpp"

namespace climbsim::launcher {

namespace {
bool processExists(pid_t pid) { return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM); }

std::string describe(const ProcessState& process, bool supervised) {
  if (process.exit_code) {
    return "exited " + std::to_string(*process.exit_code);
  }
  if (supervised && processExists(process.pid)) {
    return "running";
  }
  return "lost (its supervisor ended without seeing it exit)";
}
}  // namespace

int commandPs(const CommandContext& context) {
  const ComposeFile compose = loadComposeFile(context.compose_file);
  const RunPaths paths(context.build_dir, compose.name);
  const bool running = FileLock::isHeld(paths.lock_file);
  const std::optional<RunState> state = readRunState(paths.state_file);
  if (!state) {
    std::cout << compose.name << ": " << (running ? "starting" : "not running (no run yet)") << "\n";
    return 0;
  }
  std::cout << compose.name << ": " << (running ? "running" : "not running") << " (supervisor pid "
            << state->supervisor_pid << ", DDS domain " << state->domain_id << ", started " << state->started_at;
  if (state->exit_code) {
    std::cout << ", exit code " << *state->exit_code;
  }
  std::cout << ")\n";
  std::size_t width = 4;
  for (const auto& p : state->processes) {
    width = std::max(width, p.name.size());
  }
  std::size_t host_width = 4;
  for (const auto& p : state->processes) {
    host_width = std::max(host_width, p.host.size());
  }
  std::cout << std::left << std::setw(static_cast<int>(width + 2)) << "NAME" << std::setw(static_cast<int>(host_width + 2))
            << "HOST" << std::setw(9) << "PID" << "STATE\n";
  for (const auto& p : state->processes) {
    std::string fate = describe(p, running);
    if (p.cpu_s) {
      char cpu[32];
      std::snprintf(cpu, sizeof(cpu), ", %.2f s CPU", *p.cpu_s);
      fate += cpu;
    }
    std::cout << std::left << std::setw(static_cast<int>(width + 2)) << p.name
              << std::setw(static_cast<int>(host_width + 2)) << p.host << std::setw(9) << p.pid << fate << "\n";
  }
  return 0;
}

}  // namespace climbsim::launcher
