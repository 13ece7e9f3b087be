#include "compose_file.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "climbsim/dds_settings.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"
#include "climbsim/yaml_fields.hpp"

namespace climbsim::launcher {

namespace {
/// Options the launcher appends to every service command; a command must not set them.
constexpr const char* kLauncherOptions[] = {"--name", "--period", "--offset", "--domain"};

bool isDotsOnly(const std::string& name) { return name.find_first_not_of('.') == std::string::npos; }

/// Physical ranges of the clock's numbers: beyond them a value is a typo, and the clock's
/// integer nanoseconds would overflow.
constexpr double kMaxStep_ms = 1000.0;
constexpr double kMaxRtf = 1000.0;
constexpr double kMaxTimeout_s = 3600.0;
constexpr double kMaxDuration_s = 86400.0;

/// A number > 0 (>= 0 with `allow_zero`) and at most `max`.
double atMost(const YamlFields& f, const YAML::Node& node, const std::string& key, double max, bool allow_zero) {
  const double value = f.positive(node, key, allow_zero);
  if (value > max) {
    std::ostringstream text;
    text << "it must be a number in " << (allow_zero ? "[0, " : "(0, ") << max << "]";
    f.fail(node, key, text.str());
  }
  return value;
}

/// `has_scenario`: the file names a default scenario, whose step and duration replace the
/// clock's; duration_s and steps may then be left out.
ClockSpec parseClock(const YamlFields& f, const YAML::Node& node, bool has_scenario) {
  f.requireMap(node, "clock",
               {"step_ms", "duration_s", "steps", "rtf", "start_timeout_s", "step_timeout_s", "start_paused", "host",
                "window_steps", "max_pause_s", "control"});
  ClockSpec clock;
  bool ok = true;
  if (node["host"]) ok &= f.check([&] { clock.host = f.text(node["host"], "clock.host"); });
  if (node["step_ms"]) {
    ok &= f.check([&] {
      clock.step_ms = atMost(f, node["step_ms"], "clock.step_ms", kMaxStep_ms, false);
      if (clock.step_ms * 1e6 < 1.0) f.fail(node["step_ms"], "clock.step_ms", "a step must last at least 1 ns");
    });
  }
  if (node["rtf"]) ok &= f.check([&] { clock.rtf = atMost(f, node["rtf"], "clock.rtf", kMaxRtf, true); });
  if (node["start_timeout_s"]) {
    ok &= f.check([&] { clock.start_timeout_s = atMost(f, node["start_timeout_s"], "clock.start_timeout_s", kMaxTimeout_s, false); });
  }
  if (node["step_timeout_s"]) {
    ok &= f.check([&] { clock.step_timeout_s = atMost(f, node["step_timeout_s"], "clock.step_timeout_s", kMaxTimeout_s, false); });
  }
  if (node["start_paused"]) ok &= f.check([&] { clock.start_paused = f.boolean(node["start_paused"], "clock.start_paused"); });
  if (node["window_steps"]) {
    ok &= f.check([&] {
      clock.window_steps =
          static_cast<std::uint32_t>(f.integer(node["window_steps"], "clock.window_steps", 1, 1000000));
    });
  }
  if (node["max_pause_s"]) {
    ok &= f.check([&] { clock.max_pause_s = atMost(f, node["max_pause_s"], "clock.max_pause_s", kMaxTimeout_s, false); });
  }
  if (const YAML::Node control = node["control"]) {
    ok &= f.check([&] {
      if (!control.IsSequence()) {
        f.fail(control, "clock.control", "it must be a list of DDS participant names, e.g. [climbsim-clockctl@local, viewer]");
      }
      clock.control_line = YamlFields::lineOf(control);
      clock.control.emplace();
      for (std::size_t i = 0; i < control.size(); ++i) {
        const std::string key = "clock.control[" + std::to_string(i) + "]";
        const std::string entry = f.text(control[i], key);
        try {
          validateName(key, entry.substr(0, entry.find('@')));
        } catch (const ConfigError&) {
          f.fail(control[i], key, "give name or name@host (letters, digits, '_', '-', '.'; host from hosts:)");
        }
        clock.control->push_back(entry);
      }
    });
  }
  if (!ok) return clock;  // the relations below need valid numbers
  if (node["duration_s"] && node["steps"]) {
    f.failKey(node["steps"], "clock.steps", "give either clock.duration_s or clock.steps, not both");
  }
  if (node["steps"]) {
    clock.steps = static_cast<std::uint64_t>(
        f.integer(node["steps"], "clock.steps", 1, std::numeric_limits<long long>::max()));
    if (static_cast<double>(*clock.steps) * clock.step_ms * 1e-3 > kMaxDuration_s) {
      f.fail(node["steps"], "clock.steps", "the run would last more than a day (86400 s) of simulated time");
    }
  } else if (node["duration_s"]) {
    clock.duration_s = atMost(f, node["duration_s"], "clock.duration_s", kMaxDuration_s, false);
    if (std::llround(*clock.duration_s * 1e3 / clock.step_ms) < 1) {
      std::ostringstream step;
      step << clock.step_ms;
      f.fail(node["duration_s"], "clock.duration_s", "it is shorter than one step (" + step.str() + " ms)");
    }
  } else if (!has_scenario) {
    f.failKey(node, "clock", "give clock.duration_s or clock.steps (or a scenario:)");
  }
  return clock;
}

std::vector<std::string> parseCommand(const YamlFields& f, const YAML::Node& service, const std::string& key) {
  const YAML::Node node = service["command"];
  if (!node) {
    f.failKey(service, key, "missing; give the program and its arguments, e.g. [climbsim-test-participant, --reads, a]");
  }
  if (!node.IsSequence() || node.size() == 0) {
    f.fail(node, key, "it must be a non-empty list, e.g. [climbsim-test-participant, --reads, a]");
  }
  std::vector<std::string> command;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node item = node[i];
    if (!item.IsScalar()) {
      f.fail(item, key + "[" + std::to_string(i) + "]", "it must be a string");
    }
    command.push_back(item.Scalar());
  }
  if (command.front().empty()) {
    f.fail(node[0], key + "[0]", "the program name is empty");
  }
  for (std::size_t i = 1; i < command.size(); ++i) {
    for (const char* option : kLauncherOptions) {
      const std::string& arg = command[i];
      if (arg == option || arg.rfind(std::string(option) + "=", 0) == 0) {
        f.fail(node[i], key + "[" + std::to_string(i) + "]",
               "the launcher sets " + std::string(option) + " itself; use the service's keys and domain_id");
      }
    }
  }
  return command;
}

/// The key of an entry under `section` (a host or a service name: it names log files and
/// directories): 1..kMaxNameLength letters, digits, '_', '-' and '.', not dots only.
std::string entryName(const YamlFields& f, const YAML::Node& key_node, const std::string& section,
                      const std::string& what) {
  const std::string name = key_node.Scalar();
  const std::string key = section + "." + name;
  try {
    validateName(key, name);
    if (isDotsOnly(name)) {
      throw ConfigError("a directory name");
    }
  } catch (const ConfigError&) {
    f.failKey(key_node, key, "invalid " + what + " name; use 1.." + std::to_string(kMaxNameLength) +
                                 " letters, digits, '_', '-' and '.'");
  }
  return name;
}

/// Characters allowed in a namespace name or an ssh destination: nothing a shell would read.
bool isPlainWord(const std::string& text, const std::string& extra) {
  return !text.empty() && text.front() != '-' &&
         std::all_of(text.begin(), text.end(), [&](char c) {
           return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.' ||
                  extra.find(c) != std::string::npos;
         });
}

bool isIpv4(const std::string& text) {
  in_addr parsed{};
  return ::inet_pton(AF_INET, text.c_str(), &parsed) == 1;
}

HostSpec parseHost(const YamlFields& f, const YAML::Node& key_node, const YAML::Node& node) {
  HostSpec host;
  host.name = entryName(f, key_node, "hosts", "host");
  host.line = YamlFields::lineOf(key_node);
  const std::string key = "hosts." + host.name;
  f.requireMap(node, key, {"ssh", "netns", "address", "ssh_options"});
  if (node["ssh"] && node["netns"]) {
    f.failKey(node["netns"], key, "give either ssh: USER@HOST or netns: NAME, not both");
  }
  if (host.name == kLocalHost && (node["ssh"] || node["netns"])) {
    f.failKey(key_node, key, "'local' is this machine; only its address: may be given");
  }
  if (node["ssh"]) {
    host.kind = HostKind::ssh;
    host.target = f.text(node["ssh"], key + ".ssh");
    if (!isPlainWord(host.target, "@")) {
      f.fail(node["ssh"], key + ".ssh", "not an ssh destination USER@HOST (letters, digits, '_', '-', '.', '@')");
    }
  } else if (node["netns"]) {
    host.kind = HostKind::netns;
    host.target = f.text(node["netns"], key + ".netns");
    if (!isPlainWord(host.target, "")) {
      f.fail(node["netns"], key + ".netns", "not a network namespace name (letters, digits, '_', '-', '.')");
    }
  }
  if (const YAML::Node options = node["ssh_options"]) {
    if (host.kind != HostKind::ssh) {
      f.failKey(options, key + ".ssh_options", "only an ssh: host takes ssh options");
    }
    if (!options.IsSequence()) {
      f.fail(options, key + ".ssh_options", "it must be a list, e.g. [-p, 2222]");
    }
    for (std::size_t i = 0; i < options.size(); ++i) {
      host.ssh_options.push_back(f.text(options[i], key + ".ssh_options[" + std::to_string(i) + "]"));
    }
  }
  if (node["address"]) {
    host.address = f.text(node["address"], key + ".address");
    if (!isIpv4(host.address)) {
      f.fail(node["address"], key + ".address", "not an IPv4 address like 10.77.0.2");
    }
  }
  return host;
}

std::string hostNames(const std::vector<HostSpec>& hosts) {
  std::string names;
  for (const auto& host : hosts) {
    names += (names.empty() ? "" : ", ") + host.name;
  }
  return names;
}

ServiceSpec parseService(const YamlFields& f, const YAML::Node& key_node, const YAML::Node& node) {
  ServiceSpec service;
  service.name = entryName(f, key_node, "services", "service");
  service.line = YamlFields::lineOf(key_node);
  const std::string key = "services." + service.name;
  if (service.name == kClockProcessName) {
    f.failKey(key_node, key, "the name 'clock' is reserved for the simulation clock");
  }
  f.requireMap(node, key, {"command", "period", "offset", "replicas", "host", "observer"});
  service.command = parseCommand(f, node, key + ".command");
  constexpr long long kMaxU32 = std::numeric_limits<std::uint32_t>::max();
  if (node["period"]) {
    const YAML::Node period = node["period"];
    if (period.IsScalar() && (period.Scalar() == "depth" || period.Scalar() == "laser")) {
      service.period_rate = period.Scalar();
    } else {
      service.period = static_cast<std::uint32_t>(f.integer(period, key + ".period", 1, kMaxU32));
    }
  }
  for (std::size_t i = 0; i < service.command.size(); ++i) {
    const std::string& arg = service.command[i];
    for (auto at = arg.find("${"); at != std::string::npos; at = arg.find("${", at + 1)) {
      const bool known = std::any_of(std::begin(kCommandTokens), std::end(kCommandTokens),
                                     [&](const char* token) { return arg.compare(at, std::strlen(token), token) == 0; });
      if (!known) {
        f.fail(node["command"][i], key + ".command[" + std::to_string(i) + "]",
               "unknown ${...} token; known: ${scenario}, ${out}, ${replica}, ${replicas}");
      }
    }
  }
  if (node["offset"]) {
    service.offset = static_cast<std::uint32_t>(f.integer(node["offset"], key + ".offset", 0, kMaxU32));
    // A rate-named period is known only with the scenario; buildLaunchPlan checks the offset then.
    if (service.period_rate.empty() && service.offset >= service.period) {
      f.fail(node["offset"], key + ".offset",
             "it must be < period (" + std::to_string(service.period) + ")");
    }
  }
  if (node["replicas"]) {
    service.replicas = static_cast<std::uint32_t>(f.integer(node["replicas"], key + ".replicas", 1, kMaxReplicas));
  }
  if (node["host"]) {
    service.host = f.text(node["host"], key + ".host");
  }
  if (node["observer"]) {
    service.observer = f.boolean(node["observer"], key + ".observer");
    for (const char* schedule_key : {"period", "offset"}) {
      if (service.observer && node[schedule_key]) {
        f.fail(node[schedule_key], key + "." + schedule_key, "an observer has no schedule (it is not on the roster)");
      }
    }
  }
  for (const auto& instance : service.instanceNames()) {
    if (instance.size() > kMaxNameLength) {
      f.fail(node["replicas"], key + ".replicas",
             "the instance name '" + instance + "' is longer than " + std::to_string(kMaxNameLength) + " characters");
    }
  }
  return service;
}
}  // namespace

std::vector<std::string> ServiceSpec::instanceNames() const {
  if (replicas <= 1) {
    return {name};
  }
  std::vector<std::string> names;
  for (std::uint32_t i = 0; i < replicas; ++i) {
    names.push_back(name + "-" + std::to_string(i));
  }
  return names;
}

std::vector<std::string> ComposeFile::roster() const {
  std::vector<std::string> names;
  for (const auto& service : services) {
    if (service.observer) continue;
    for (auto& instance : service.instanceNames()) {
      names.push_back(std::move(instance));
    }
  }
  return names;
}

ComposeFile parseComposeText(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = YamlFields::load(yaml_text, source);
  const YamlFields f(source);
  if (!root.IsDefined() || root.IsNull()) {
    throw ConfigError(source + ": the file is empty; it needs name, clock and services");
  }
  f.requireMap(root, "(top level)", {"name", "domain_id", "scenario", "security", "clock", "hosts", "services"});

  ComposeFile compose;
  compose.source = source;
  if (!root["name"]) {
    f.check([&] { f.failKey(root, "name", "missing; give the composition a name (used for its run directory)"); });
  } else {
    f.check([&] {
      compose.name = f.text(root["name"], "name");
      try {
        validateName("name", compose.name);
        if (isDotsOnly(compose.name)) {
          throw ConfigError("a directory name");  // it names the run directory
        }
      } catch (const ConfigError&) {
        f.fail(root["name"], "name",
               "use 1.." + std::to_string(kMaxNameLength) + " letters, digits, '_', '-' and '.'");
      }
    });
  }

  if (root["domain_id"] && !(root["domain_id"].IsScalar() && root["domain_id"].Scalar() == "auto")) {
    f.check([&] { compose.domain_id = static_cast<int>(f.integer(root["domain_id"], "domain_id", 0, kMaxDomainId)); });
  }

  if (root["scenario"]) {
    f.check([&] {
      const std::filesystem::path scenario(f.text(root["scenario"], "scenario"));
      compose.scenario = scenario.is_absolute()
                             ? scenario.lexically_normal().string()
                             : (std::filesystem::absolute(source).parent_path() / scenario).lexically_normal().string();
      compose.scenario_line = YamlFields::lineOf(root["scenario"]);
    });
  }

  if (root["security"]) {
    f.check([&] { compose.security = f.boolean(root["security"], "security"); });
  }

  if (!root["clock"]) {
    f.check([&] { f.failKey(root, "clock", "missing; give at least clock.duration_s or clock.steps"); });
  } else {
    f.check([&] { compose.clock = parseClock(f, root["clock"], root["scenario"].IsDefined()); });
  }

  compose.hosts.push_back(HostSpec{kLocalHost, HostKind::local, "", "", {}, 0});
  // Hosts whose entry has a problem (reported once): their users are not blamed again.
  std::set<std::string> bad_hosts;
  if (const YAML::Node hosts = root["hosts"]) {
    f.check([&] {
      f.requireMapAnyKeys(hosts, "hosts");
      std::set<std::string> seen;
      for (const auto& item : hosts) {
        if (!seen.insert(item.first.Scalar()).second) continue;  // a duplicate key, reported
        const bool ok = f.check([&] {
          HostSpec host = parseHost(f, item.first, item.second);
          if (host.name == kLocalHost) {
            compose.hosts.front() = std::move(host);
          } else {
            compose.hosts.push_back(std::move(host));
          }
        });
        if (!ok) bad_hosts.insert(item.first.Scalar());
      }
    });
  }
  const auto requireKnownHost = [&](const std::string& name, const YAML::Node& node, const std::string& key) {
    const bool known = bad_hosts.count(name) != 0 ||
                       std::any_of(compose.hosts.begin(), compose.hosts.end(),
                                   [&](const HostSpec& host) { return host.name == name; });
    if (!known) {
      f.fail(node, key, "unknown host; define it under hosts: (known: " + hostNames(compose.hosts) + ")");
    }
  };
  if (root["clock"] && root["clock"].IsMap() && root["clock"]["host"]) {
    f.check([&] { requireKnownHost(compose.clock.host, root["clock"]["host"], "clock.host"); });
  }
  if (compose.clock.control && root["clock"].IsMap() && root["clock"]["control"].IsSequence()) {
    for (std::size_t i = 0; i < compose.clock.control->size(); ++i) {
      const std::string& entry = (*compose.clock.control)[i];
      if (entry.find('@') != std::string::npos) {
        f.check([&] {
          requireKnownHost(entry.substr(entry.find('@') + 1), root["clock"]["control"][i],
                           "clock.control[" + std::to_string(i) + "]");
        });
      }
    }
  }

  const YAML::Node services = root["services"];
  if (!services) {
    f.check([&] { f.failKey(root, "services", "missing; list the services to run"); });
  } else {
    f.check([&] {
      f.requireMapAnyKeys(services, "services");
      if (services.size() == 0) {
        f.fail(services, "services", "there must be at least one service");
      }
      std::set<std::string> instances;
      std::set<std::string> seen;
      for (const auto& item : services) {
        if (!seen.insert(item.first.Scalar()).second) continue;  // a duplicate key, reported
        f.check([&] {
          ServiceSpec service = parseService(f, item.first, item.second);
          for (const auto& instance : service.instanceNames()) {
            if (!instances.insert(instance).second) {
              f.failKey(item.first, "services." + service.name,
                        "the instance name '" + instance + "' is already used by another service");
            }
          }
          requireKnownHost(service.host, item.second["host"], "services." + service.name + ".host");
          compose.services.push_back(std::move(service));
        });
      }
    });
  }
  f.finish();
  if (compose.multiHost()) {
    for (const HostSpec* host : compose.usedHosts()) {
      if (host->address.empty()) {
        const YAML::Node where = host->line > 0 ? root["hosts"][host->name] : root;
        f.check([&] {
          f.failKey(where, "hosts." + host->name + ".address",
                    "missing; every host of a multi-host composition needs the IPv4 address the others reach it at");
        });
      }
    }
    std::set<std::string> addresses;
    for (const HostSpec* host : compose.usedHosts()) {
      if (!addresses.insert(host->address).second) {
        f.check([&] {
          f.fail(root["hosts"][host->name]["address"], "hosts." + host->name + ".address",
                 "another used host has the same address");
        });
      }
    }
  }
  f.finish();
  return compose;
}

const HostSpec& ComposeFile::host(const std::string& name) const {
  for (const auto& host : hosts) {
    if (host.name == name) return host;
  }
  throw std::out_of_range("no host '" + name + "' in " + source);
}

std::vector<const HostSpec*> ComposeFile::usedHosts() const {
  std::vector<const HostSpec*> used;
  for (const auto& host : hosts) {
    const bool runs_something =
        clock.host == host.name ||
        std::any_of(services.begin(), services.end(), [&](const ServiceSpec& s) { return s.host == host.name; });
    if (runs_something) used.push_back(&host);
  }
  return used;
}

bool ComposeFile::multiHost() const {
  const auto used = usedHosts();
  return used.size() > 1 || (used.size() == 1 && used.front()->kind != HostKind::local);
}

ComposeFile loadComposeFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw ConfigError(path + ": cannot read the compose file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parseComposeText(text.str(), path);
}

}  // namespace climbsim::launcher
