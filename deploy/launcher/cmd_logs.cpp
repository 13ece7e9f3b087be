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
#include "run_state.hpp"

namespace climbsim::launcher {

namespace {
/// The processes `service` names: a process, or every instance of a replicated service.
std::vector<std::string> selectProcesses(const ComposeFile& compose, const std::string& service) {
  std::vector<std::string> all{kClockProcessName};
  for (const auto& name : compose.roster()) {
    all.push_back(name);
  }
  if (service.empty()) {
    return all;
  }
  if (std::find(all.begin(), all.end(), service) != all.end()) {
    return {service};
  }
  for (const auto& spec : compose.services) {
    if (spec.name == service) {
      return spec.instanceNames();
    }
  }
  std::string known;
  for (const auto& name : all) {
    known += (known.empty() ? "" : ", ") + name;
  }
  throw ConfigError("logs: no service '" + service + "' in " + compose.source + " (known: " + known + ")");
}
}  // namespace

int commandLogs(const CommandContext& context, const std::string& service) {
  const ComposeFile compose = loadComposeFile(context.compose_file);
  const RunPaths paths(context.build_dir, compose.name);
  const std::vector<std::string> names = selectProcesses(compose, service);
  const bool prefixed = names.size() > 1;
  const bool color = prefixed && terminalWantsColor();
  std::size_t width = 0;
  for (const auto& name : names) {
    width = std::max(width, name.size());
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
    spdlog::info("no logs of '{}' yet (in {})", service.empty() ? compose.name : service, paths.logs_dir);
  }
  return 0;
}

}  // namespace climbsim::launcher
