#include "launch_plan.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <filesystem>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {

namespace {
bool isExecutableFile(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

std::string joinPath(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).lexically_normal().string();
}
}  // namespace

std::string formatNumber(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

std::string resolveExecutable(const std::string& program, const std::string& key, const ExecutableSearch& search) {
  if (program.find('/') != std::string::npos) {
    const std::string path = program.front() == '/' ? program : joinPath(search.compose_dir, program);
    if (!isExecutableFile(path)) {
      throw ConfigError(key + " = " + program + ": '" + path + "' is not an executable file");
    }
    return path;
  }
  if (!search.bin_dir.empty()) {
    const std::string in_bin = joinPath(search.bin_dir, program);
    if (isExecutableFile(in_bin)) {
      return in_bin;
    }
  }
  std::size_t begin = 0;
  while (begin <= search.path_env.size()) {
    const std::size_t colon = search.path_env.find(':', begin);
    const std::string dir = search.path_env.substr(begin, colon == std::string::npos ? std::string::npos : colon - begin);
    if (!dir.empty() && isExecutableFile(joinPath(dir, program))) {
      return joinPath(dir, program);
    }
    if (colon == std::string::npos) {
      break;
    }
    begin = colon + 1;
  }
  throw ConfigError(key + " = " + program + ": no such program in " +
                    (search.bin_dir.empty() ? std::string() : search.bin_dir + " or ") +
                    "on PATH (is the build complete?)");
}

namespace {
/// `arg` with every occurrence of `token` replaced by `value`.
std::string replaced(std::string arg, const std::string& token, const std::string& value) {
  for (auto at = arg.find(token); at != std::string::npos; at = arg.find(token, at + value.size())) {
    arg.replace(at, token.size(), value);
  }
  return arg;
}
}  // namespace

LaunchPlan buildLaunchPlan(const ComposeFile& compose, int domain_id, const ExecutableSearch& search,
                           const std::optional<ScenarioRun>& scenario) {
  LaunchPlan plan;
  plan.domain_id = domain_id;
  const std::string domain = std::to_string(domain_id);

  ProcessLaunch clock;
  clock.name = kClockProcessName;
  clock.argv = {resolveExecutable("climbsim-clock", compose.source + ": clock program", search),
                "--roster", "", "--step-ms", formatNumber(scenario ? scenario->step_ms : compose.clock.step_ms)};
  std::string roster;
  for (const auto& name : compose.roster()) {
    roster += (roster.empty() ? "" : ",") + name;
  }
  clock.argv[2] = roster;
  if (scenario) {
    clock.argv.insert(clock.argv.end(), {"--duration-s", formatNumber(scenario->duration_s)});
  } else if (compose.clock.steps) {
    clock.argv.insert(clock.argv.end(), {"--steps", std::to_string(*compose.clock.steps)});
  } else if (compose.clock.duration_s) {
    clock.argv.insert(clock.argv.end(), {"--duration-s", formatNumber(*compose.clock.duration_s)});
  }
  clock.argv.insert(clock.argv.end(), {"--rtf", formatNumber(compose.clock.rtf),
                                       "--start-timeout-s", formatNumber(compose.clock.start_timeout_s),
                                       "--step-timeout-s", formatNumber(compose.clock.step_timeout_s)});
  if (compose.clock.start_paused) {
    clock.argv.emplace_back("--start-paused");
  }
  clock.argv.insert(clock.argv.end(), {"--domain", domain});
  plan.processes.push_back(std::move(clock));

  for (const auto& service : compose.services) {
    const std::string where = compose.source + ":" + std::to_string(service.line) + ": services." + service.name;
    const std::string program = resolveExecutable(service.command.front(), where + ".command[0]", search);
    std::uint32_t period = service.period;
    if (!service.period_rate.empty()) {
      if (!scenario) {
        throw ConfigError(where + ".period = " + service.period_rate + ": a rate-named period needs a scenario (--scenario)");
      }
      period = service.period_rate == "depth" ? scenario->depth_period : scenario->laser_period;
      if (service.offset >= period) {
        throw ConfigError(where + ".offset = " + std::to_string(service.offset) + ": it must be < the scenario's " +
                          service.period_rate + " period (" + std::to_string(period) + " steps)");
      }
    }
    const auto instances = service.instanceNames();
    for (std::size_t replica = 0; replica < instances.size(); ++replica) {
      ProcessLaunch launch;
      launch.name = instances[replica];
      launch.argv = service.command;
      launch.argv.front() = program;
      for (std::size_t i = 1; i < launch.argv.size(); ++i) {
        std::string& arg = launch.argv[i];
        if ((arg.find("${scenario}") != std::string::npos || arg.find("${out}") != std::string::npos) && !scenario) {
          throw ConfigError(where + ".command[" + std::to_string(i) + "] = " + arg +
                            ": ${scenario} and ${out} need a scenario (--scenario or the file's scenario:)");
        }
        if (scenario) {
          arg = replaced(replaced(arg, "${scenario}", scenario->scenario_file), "${out}", scenario->out_dir);
        }
        arg = replaced(replaced(arg, "${replicas}", std::to_string(instances.size())), "${replica}",
                       std::to_string(replica));
      }
      launch.argv.insert(launch.argv.end(), {"--name", launch.name,
                                             "--period", std::to_string(period),
                                             "--offset", std::to_string(service.offset),
                                             "--domain", domain});
      plan.processes.push_back(std::move(launch));
    }
  }
  return plan;
}

}  // namespace climbsim::launcher
