/// `logs`: print what the processes of a composition wrote.

#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "commands.hpp"
#include "compose_file.hpp"
#include "output_router.hpp"
#include "run_registry.hpp"
#include "run_state.hpp"

namespace climbsim::launcher {

namespace {
/// The processes `service` names: a process, or every instance of a replicated service.
std::vector<std::string> selectProcesses(const RunEntry& run, const std::string& service) {
  std::vector<std::string> all;
  if (run.state) {
    for (const auto& p : run.state->processes) all.push_back(p.name);
  }
  if (all.empty()) all.push_back(kClockProcessName);
  if (service.empty()) {
    return all;
  }
  if (std::find(all.begin(), all.end(), service) != all.end()) {
    return {service};
  }
  // A replicated service's instances are NAME-0 .. NAME-N-1.
  std::vector<std::string> instances;
  for (const auto& name : all) {
    const auto dash = name.rfind('-');
    if (dash != std::string::npos && name.substr(0, dash) == service &&
        name.find_first_not_of("0123456789", dash + 1) == std::string::npos && dash + 1 < name.size()) {
      instances.push_back(name);
    }
  }
  if (!instances.empty()) return instances;
  std::string known;
  for (const auto& name : all) {
    known += (known.empty() ? "" : ", ") + name;
  }
  throw ConfigError("logs: no service '" + service + "' in run '" + run.name + "' (known: " + known + ")");
}
}  // namespace

int commandLogs(const CommandContext& context, const std::string& name, const std::string& service) {
  const std::string filter = context.compose_given ? context.compose_file : std::string();
  std::string run_name = name;
  std::string process = service;
  // `logs SERVICE` with one run: the single word names a service unless it names a run.
  if (!name.empty() && service.empty()) {
    bool is_run = false;
    for (const auto& run : listRuns(context.build_dir)) is_run = is_run || run.name == name;
    if (!is_run) {
      run_name.clear();
      process = name;
    }
  }
  const std::optional<RunEntry> run = selectRun(context.build_dir, run_name, filter, true);
  if (!run) {
    spdlog::info("no runs yet (in {}/run)", context.build_dir);
    return 0;
  }
  const RunPaths& paths = run->paths;
  if (run_name.empty()) {
    // Not named: say whose logs these are (on stderr, so that the logs themselves stay clean).
    std::cerr << "logs of run '" << run->name << "'" << (run->running ? "" : " (the last run; not running)")
              << std::endl;
  }
  const std::vector<std::string> names = selectProcesses(*run, process);
  const bool prefixed = names.size() > 1;
  const bool color = prefixed && terminalWantsColor();
  std::size_t width = 0;
  for (const auto& n : names) {
    width = std::max(width, n.size());
  }
  std::size_t found = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::ifstream in(paths.logFile(names[i]));
    if (!in) {
      continue;
    }
    ++found;
    const std::string prefix = prefixed ? linePrefix(names[i], width, i, color) : std::string();
    std::string line;
    while (std::getline(in, line)) {
      std::cout << prefix << line << '\n';
    }
  }
  std::cout.flush();
  if (found == 0) {
    spdlog::info("no logs of '{}' yet (in {})", process.empty() ? run->name : process, paths.logs_dir);
  }
  return 0;
}

}  // namespace climbsim::launcher
