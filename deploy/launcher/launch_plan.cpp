#include "launch_plan.hpp"

#include <ifaddrs.h>
#include <netinet/in.h>
#include <arpa/inet.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <random>

#include "climbsim/dds_discovery_env.hpp"
#include "climbsim/dds_security_env.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/run_id_env.hpp"

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

ExecutableSearch executableSearch(const std::string& compose_file, const std::string& build_dir,
                                  const std::string& path_env) {
  return ExecutableSearch{joinPath(build_dir, "bin"),
                          std::filesystem::absolute(compose_file).lexically_normal().parent_path().string(), path_env};
}

std::string resolveExecutable(const std::string& program, const std::string& key, const ExecutableSearch& search) {
  if (program.find('/') != std::string::npos) {
    const std::string path = program.front() == '/' ? program : joinPath(search.compose_dir, program);
    if (isExecutableFile(path)) return path;
    std::string why = std::filesystem::exists(path) ? "is not an executable file" : "does not exist";
    if (program.front() != '/') why += " (a relative path is taken from the compose file's folder)";
    const std::string name = std::filesystem::path(program).filename().string();
    if (!search.bin_dir.empty() && isExecutableFile(joinPath(search.bin_dir, name))) {
      why += "; a program of the build is named alone: " + name + " (found in " + search.bin_dir + ")";
    }
    throw ConfigError(key + " = " + program + ": '" + path + "' " + why);
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

namespace {
bool onPath(const std::string& program, const std::string& path_env) {
  std::size_t begin = 0;
  while (begin <= path_env.size()) {
    const std::size_t colon = path_env.find(':', begin);
    const std::string dir = path_env.substr(begin, colon == std::string::npos ? std::string::npos : colon - begin);
    if (!dir.empty() && isExecutableFile(joinPath(dir, program))) return true;
    if (colon == std::string::npos) break;
    begin = colon + 1;
  }
  return false;
}
}  // namespace

void checkHosts(const ComposeFile& compose, const std::string& path_env) {
  for (const HostSpec* host : compose.usedHosts()) {
    const std::string where = compose.source + ":" + std::to_string(host->line) + ": hosts." + host->name;
    if (host->kind == HostKind::netns) {
      if (!std::filesystem::exists("/run/netns/" + host->target)) {
        throw ConfigError(where + ".netns = " + host->target + ": no such network namespace (/run/netns/" +
                          host->target + "); make it first, e.g. `./deploy/climbsim hosts up` for climbsim-b");
      }
      if (!onPath("ip", path_env)) {
        throw ConfigError(where + ".netns = " + host->target + ": the program 'ip' (iproute2) is not on PATH");
      }
    } else if (host->kind == HostKind::ssh && !onPath("ssh", path_env)) {
      throw ConfigError(where + ".ssh = " + host->target + ": the program 'ssh' (openssh-client) is not on PATH");
    }
  }
}

std::string shellQuoted(const std::string& word) {
  std::string quoted = "'";
  for (const char c : word) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

std::vector<std::string> commandOnHost(const HostSpec& host, const std::vector<std::string>& argv,
                                       const std::map<std::string, std::string>& env) {
  switch (host.kind) {
    case HostKind::local:
      return argv;
    case HostKind::netns: {
      std::vector<std::string> command = {"ip", "netns", "exec", host.target};
      command.insert(command.end(), argv.begin(), argv.end());
      return command;
    }
    case HostKind::ssh: {
      std::string remote = "exec env";
      for (const auto& [key, value] : env) {
        remote += " " + shellQuoted(key + "=" + value);
      }
      for (const auto& word : argv) {
        remote += " " + shellQuoted(word);
      }
      std::vector<std::string> command = {"ssh", "-tt", "-o", "BatchMode=yes", "-o", "LogLevel=ERROR"};
      command.insert(command.end(), host.ssh_options.begin(), host.ssh_options.end());
      command.insert(command.end(), {host.target, "--", remote});
      return command;
    }
  }
  return argv;
}

std::map<std::string, std::string> discoveryEnvironment(const ComposeFile& compose, const HostSpec& host) {
  if (!compose.multiHost()) {
    return {};
  }
  std::string peers;
  std::size_t most_processes = 1;
  for (const HostSpec* used : compose.usedHosts()) {
    peers += (peers.empty() ? "" : ",") + used->address;
    std::size_t processes = compose.clock.host == used->name ? 1 : 0;
    for (const auto& service : compose.services) {
      if (service.host == used->name) processes += service.replicas;
    }
    most_processes = std::max(most_processes, processes);
  }
  // Fast DDS numbers the participants of a host from 0; a few ids to spare for observers
  // (a viewer, a controller in another language) that join the run on the same host.
  const std::size_t range = std::min<std::size_t>(120, most_processes + 8);
  return {{kEnvDdsPeers, peers}, {kEnvDdsInterface, host.address}, {kEnvDdsPeerRange, std::to_string(range)}};
}

std::vector<std::string> localAddresses() {
  std::vector<std::string> addresses;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) {
    return {"127.0.0.1"};
  }
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {0};
    const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
    if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text) != nullptr &&
        std::find(addresses.begin(), addresses.end(), text) == addresses.end()) {
      addresses.emplace_back(text);
    }
  }
  ::freeifaddrs(list);
  return addresses;
}

std::string controlSenders(const ComposeFile& compose) {
  std::vector<std::string> entries;
  if (compose.clock.control) {
    entries = *compose.clock.control;
  } else {
    entries.push_back(std::string(kClockCtlName) + "@" + kLocalHost);
    for (const auto& service : compose.services) {
      const std::string program = std::filesystem::path(service.command.front()).filename().string();
      if (service.observer && program == "climbsim-viewer") {
        for (const auto& instance : service.instanceNames()) entries.push_back(instance + "@" + service.host);
      }
    }
  }
  std::string text;
  for (const auto& entry : entries) {
    const std::size_t at = entry.find('@');
    std::string item = entry.substr(0, at);
    if (at != std::string::npos) {
      const HostSpec& host = compose.host(entry.substr(at + 1));
      std::vector<std::string> addresses;
      if (host.kind == HostKind::local) addresses = localAddresses();
      if (!host.address.empty() && std::find(addresses.begin(), addresses.end(), host.address) == addresses.end()) {
        addresses.push_back(host.address);
      }
      if (host.name == compose.clock.host) {
        addresses.emplace_back("shm");  // the clock's machine: the clock reaches it by shared memory
      }
      if (addresses.empty()) {
        throw ConfigError(compose.source + ":" + std::to_string(compose.clock.control_line) + ": clock.control entry '" +
                          entry + "': host '" + host.name + "' has no address; give hosts." + host.name + ".address");
      }
      for (std::size_t i = 0; i < addresses.size(); ++i) item += (i == 0 ? "@" : "/") + addresses[i];
    }
    text += (text.empty() ? "" : ",") + item;
  }
  return text;
}

std::uint64_t randomRunId() {
  std::random_device random;
  std::uint64_t id = 0;
  while (id == 0) {
    id = static_cast<std::uint64_t>(random()) << 32 | random();
  }
  return id;
}

LaunchPlan buildLaunchPlan(const ComposeFile& compose, int domain_id, const ExecutableSearch& search,
                           const std::optional<ScenarioRun>& scenario, std::optional<std::uint64_t> run_id,
                           const std::string& security_dir) {
  LaunchPlan plan;
  plan.domain_id = domain_id;
  plan.run_id = run_id;
  auto with_run_id = [&](std::map<std::string, std::string> env, const std::string& identity) {
    if (run_id) {
      env[kEnvRunId] = std::to_string(*run_id);
    }
    if (std::error_code ec; std::filesystem::is_regular_file(compose.source, ec)) {
      env[kEnvComposeFile] = std::filesystem::absolute(compose.source).lexically_normal().string();
    }
    if (!security_dir.empty()) {
      env[kEnvSecurityDir] = security_dir;
      env[kEnvSecurityIdentity] = identity;
    }
    return env;
  };
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
    if (!scenario->robot_file.empty()) {
      clock.argv.insert(clock.argv.end(), {"--robot", scenario->robot_file});  // RunStart carries the robot
    }
  } else if (compose.clock.steps) {
    clock.argv.insert(clock.argv.end(), {"--steps", std::to_string(*compose.clock.steps)});
  } else if (compose.clock.duration_s) {
    clock.argv.insert(clock.argv.end(), {"--duration-s", formatNumber(*compose.clock.duration_s)});
  }
  clock.argv.insert(clock.argv.end(), {"--rtf", formatNumber(compose.clock.rtf),
                                       "--start-timeout-s", formatNumber(compose.clock.start_timeout_s),
                                       "--step-timeout-s", formatNumber(compose.clock.step_timeout_s)});
  if (compose.clock.window_steps) {
    clock.argv.insert(clock.argv.end(), {"--window-steps", std::to_string(*compose.clock.window_steps)});
  }
  if (compose.clock.start_paused) {
    clock.argv.emplace_back("--start-paused");
  }
  clock.argv.insert(clock.argv.end(), {"--domain", domain});
  if (run_id) {
    clock.argv.insert(clock.argv.end(), {"--run-id", std::to_string(*run_id)});
  }
  if (compose.clock.max_pause_s) {
    clock.argv.insert(clock.argv.end(), {"--max-pause-s", formatNumber(*compose.clock.max_pause_s)});
  }
  clock.argv.insert(clock.argv.end(), {"--control-from", controlSenders(compose)});
  const HostSpec& clock_host = compose.host(compose.clock.host);
  clock.host = clock_host.name;
  clock.env = with_run_id(discoveryEnvironment(compose, clock_host), kClockProcessName);
  clock.argv = commandOnHost(clock_host, clock.argv, clock.env);
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
      if (service.observer) {
        launch.argv.insert(launch.argv.end(), {"--name", launch.name, "--domain", domain});
      } else {
        launch.argv.insert(launch.argv.end(), {"--name", launch.name,
                                               "--period", std::to_string(period),
                                               "--offset", std::to_string(service.offset),
                                               "--domain", domain});
      }
      const HostSpec& host = compose.host(service.host);
      launch.host = host.name;
      launch.observer = service.observer;
      launch.env = with_run_id(discoveryEnvironment(compose, host), launch.name);
      launch.argv = commandOnHost(host, launch.argv, launch.env);
      plan.processes.push_back(std::move(launch));
    }
  }
  return plan;
}

}  // namespace climbsim::launcher
