/// `ps`: the processes of a composition and what became of them.

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "file_lock.hpp"
#include "run_registry.hpp"
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

namespace {
void printProcesses(const RunEntry& run) {
  const RunState& state = *run.state;
  std::cout << run.name << ": " << (run.running ? "running" : "not running") << " (supervisor pid "
            << state.supervisor_pid << ", DDS domain " << state.domain_id << ", started " << state.started_at;
  if (state.exit_code) {
    std::cout << ", exit code " << *state.exit_code;
  }
  if (!state.viewer_url.empty()) std::cout << ", viewer " << state.viewer_url;
  std::cout << ")\n";
  std::size_t width = 4;
  std::size_t host_width = 4;
  for (const auto& p : state.processes) {
    width = std::max(width, p.name.size());
    host_width = std::max(host_width, p.host.size());
  }
  std::cout << std::left << std::setw(static_cast<int>(width + 2)) << "NAME" << std::setw(static_cast<int>(host_width + 2))
            << "HOST" << std::setw(9) << "PID" << "STATE\n";
  for (const auto& p : state.processes) {
    std::string fate = describe(p, run.running);
    if (p.cpu_s) {
      char cpu[32];
      std::snprintf(cpu, sizeof(cpu), ", %.2f s CPU", *p.cpu_s);
      fate += cpu;
    }
    std::cout << std::left << std::setw(static_cast<int>(width + 2)) << p.name
              << std::setw(static_cast<int>(host_width + 2)) << p.host << std::setw(9) << p.pid << fate << "\n";
  }
}

std::string runFate(const RunEntry& run) {
  if (!run.state) return run.running ? "starting" : "unknown";
  if (run.running) return "running";
  return run.state->exit_code ? "exited " + std::to_string(*run.state->exit_code) : "lost";
}

/// "crack-descent" for <root>/deploy/scenarios/crack-descent.yaml, else the compose file's stem.
std::string whatRuns(const RunState& state) {
  namespace fs = std::filesystem;
  if (!state.scenario.empty()) return fs::path(state.scenario).stem().string();
  return fs::path(state.compose_file).filename().string();
}
}  // namespace

int commandPs(const CommandContext& context, const std::string& name) {
  const std::string filter = context.compose_given ? context.compose_file : std::string();
  if (!name.empty()) {
    const std::optional<RunEntry> run = selectRun(context.build_dir, name, filter, true);
    if (!run->state) {
      std::cout << run->name << ": " << (run->running ? "starting" : "not running (no state)") << "\n";
      return 0;
    }
    printProcesses(*run);
    return 0;
  }
  std::vector<RunEntry> runs = listRuns(context.build_dir);
  if (!filter.empty()) {
    runs.erase(std::remove_if(runs.begin(), runs.end(),
                              [&](const RunEntry& r) { return !r.state || r.state->compose_file != filter; }),
               runs.end());
  }
  if (runs.empty()) {
    std::cout << "no runs yet (in " << context.build_dir << "/run)\n";
    return 0;
  }
  std::size_t width = 3;
  for (const auto& run : runs) width = std::max(width, run.name.size());
  const auto column = [](std::size_t w) { return std::setw(static_cast<int>(w)); };
  std::cout << std::left << column(width + 2) << "RUN" << column(11) << "STATE" << column(8) << "DOMAIN" << column(6)
            << "RTF" << column(21) << "STARTED" << column(9) << "PID" << "SCENARIO / OUTPUT\n";
  for (const auto& run : runs) {
    std::cout << std::left << column(width + 2) << run.name << column(11) << runFate(run);
    if (run.state) {
      char rtf[16];
      std::snprintf(rtf, sizeof(rtf), "%g", run.state->rtf);
      std::cout << column(8) << run.state->domain_id << column(6) << rtf << column(21) << run.state->started_at
                << column(9) << run.state->supervisor_pid << whatRuns(*run.state)
                << (run.state->out_dir.empty() ? "" : " -> " + run.state->out_dir);
    }
    std::cout << "\n";
  }
  for (const auto& run : runs) {
    if (!run.running || !run.state) continue;
    std::cout << "\n";
    printProcesses(run);
  }
  return 0;
}

}  // namespace climbsim::launcher
