#include "compose_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {
namespace {

const std::string kDemo = R"(name: demo
domain_id: auto
clock: {step_ms: 5, duration_s: 10, rtf: 1.0, start_timeout_s: 30, step_timeout_s: 10}
services:
  a: {command: [climbsim-test-participant, --reads, "b,c"], period: 1, offset: 0}
  b: {command: [climbsim-test-participant, --reads, "a"], period: 2, offset: 1}
  c: {command: [climbsim-test-participant, --reads, "a,b"], period: 4, offset: 3, replicas: 1, host: local}
)";

/// The ConfigError message parsing `text` gives, or "" if it parses.
std::string errorOf(const std::string& text) {
  try {
    parseComposeText(text, "x.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

/// kDemo with `from` replaced by `to` (which must occur).
std::string demoWith(const std::string& from, const std::string& to) {
  std::string text = kDemo;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// Expects a one-line error naming the file and containing every one of `parts`.
void expectError(const std::string& text, std::initializer_list<std::string> parts) {
  const std::string message = errorOf(text);
  ASSERT_FALSE(message.empty()) << "no error for:\n" << text;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind("x.yaml", 0), 0u) << message;
  for (const auto& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

TEST(ComposeFile, ParsesTheDemo) {
  const ComposeFile compose = parseComposeText(kDemo, "x.yaml");
  EXPECT_EQ(compose.name, "demo");
  EXPECT_FALSE(compose.domain_id);
  EXPECT_DOUBLE_EQ(compose.clock.step_ms, 5.0);
  ASSERT_TRUE(compose.clock.duration_s);
  EXPECT_DOUBLE_EQ(*compose.clock.duration_s, 10.0);
  EXPECT_FALSE(compose.clock.steps);
  EXPECT_DOUBLE_EQ(compose.clock.rtf, 1.0);
  ASSERT_EQ(compose.services.size(), 3u);
  EXPECT_EQ(compose.services[1].name, "b");
  EXPECT_EQ(compose.services[1].period, 2u);
  EXPECT_EQ(compose.services[1].offset, 1u);
  EXPECT_EQ(compose.services[2].command,
            (std::vector<std::string>{"climbsim-test-participant", "--reads", "a,b"}));
  EXPECT_EQ(compose.services[2].host, "local");
  EXPECT_EQ(compose.roster(), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(ComposeFile, ObserversAreNotOnTheRoster) {
  const auto compose = parseComposeText(
      std::string(kDemo) + "  viewer: {command: [climbsim-viewer, --port, \"8765\"], observer: true}\n", "x.yaml");
  ASSERT_EQ(compose.services.size(), 4u);
  EXPECT_TRUE(compose.services[3].observer);
  EXPECT_FALSE(compose.services[0].observer);
  EXPECT_EQ(compose.roster(), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(ComposeFile, ObserverWithAScheduleIsRejected) {
  expectError(std::string(kDemo) + "  viewer: {command: [climbsim-viewer], observer: true, period: 2}\n",
              {"services.viewer.period", "an observer has no schedule"});
  expectError(std::string(kDemo) + "  viewer: {command: [climbsim-viewer], observer: maybe}\n",
              {"services.viewer.observer"});
}

TEST(ComposeFile, SecurityOnOrOff) {
  const auto secured = parseComposeText("name: n\nsecurity: on\nclock: {steps: 1}\nservices:\n  s: {command: [x]}\n", "x.yaml");
  EXPECT_TRUE(secured.security);
  const auto plain = parseComposeText("name: n\nclock: {steps: 1}\nservices:\n  s: {command: [x]}\n", "x.yaml");
  EXPECT_FALSE(plain.security);
  expectError("name: n\nsecurity: maybe\nclock: {steps: 1}\nservices:\n  s: {command: [x]}\n",
              {"x.yaml:2", "security = maybe"});
}

TEST(ComposeFile, FixedDomainAndSteps) {
  const auto compose = parseComposeText(
      "name: n\ndomain_id: 42\nclock: {steps: 100, start_paused: true}\nservices:\n  s: {command: [x]}\n", "x.yaml");
  EXPECT_EQ(compose.domain_id, 42);
  EXPECT_EQ(compose.clock.steps, 100u);
  EXPECT_TRUE(compose.clock.start_paused);
  EXPECT_EQ(compose.services[0].period, 1u);
  EXPECT_EQ(compose.services[0].offset, 0u);
}

TEST(ComposeFile, ReplicasGetNumberedNames) {
  const auto compose = parseComposeText(demoWith("replicas: 1", "replicas: 3"), "x.yaml");
  EXPECT_EQ(compose.roster(), (std::vector<std::string>{"a", "b", "c-0", "c-1", "c-2"}));
}

TEST(ComposeFile, RejectsPeriodZero) {
  expectError(demoWith("period: 2", "period: 0"), {"x.yaml:6", "services.b.period = 0", ">= 1"});
}

TEST(ComposeFile, RejectsOffsetNotBelowPeriod) {
  expectError(demoWith("period: 4, offset: 3", "period: 4, offset: 4"), {"services.c.offset = 4", "< period (4)"});
}

TEST(ComposeFile, RejectsBadDomainIds) {
  expectError(demoWith("domain_id: auto", "domain_id: 233"), {"domain_id = 233", "0..232"});
  expectError(demoWith("domain_id: auto", "domain_id: -1"), {"domain_id = -1"});
  expectError(demoWith("domain_id: auto", "domain_id: automatic"), {"domain_id = automatic"});
  expectError(demoWith("domain_id: auto", "domain_id: 4.5"), {"domain_id = 4.5"});
  EXPECT_EQ(errorOf(demoWith("domain_id: auto", "domain_id: 232")), "");
  EXPECT_EQ(errorOf(demoWith("domain_id: auto", "domain_id: 0")), "");
}

TEST(ComposeFile, RejectsUnknownKeys) {
  expectError(demoWith("name: demo", "name: demo\nversion: 3"), {"version", "unknown key"});
  expectError(demoWith("period: 1,", "perod: 1,"), {"services.a.perod", "unknown key"});
  expectError(demoWith("rtf: 1.0", "rtf: 1.0, speed: 2"), {"clock.speed", "unknown key"});
}

TEST(ComposeFile, RejectsDuplicateAndInvalidNames) {
  expectError(demoWith("  b: {", "  a: {"), {"services.a", "duplicate"});
  expectError(demoWith("  b: {", "  \"b c\": {"), {"services.b c", "invalid service name"});
  expectError(demoWith("  b: {", "  " + std::string(64, 'n') + ": {"), {"invalid service name"});
  expectError(demoWith("  b: {", "  clock: {"), {"services.clock", "reserved"});
  expectError(demoWith("name: demo", "name: my/demo"), {"name = my/demo"});
  expectError(demoWith("name: demo", "name: .."), {"name = .."});
  expectError(demoWith("  b: {", "  .: {"), {"services..", "invalid service name"});
  // a replica name that another service already has
  expectError(demoWith("replicas: 1", "replicas: 2") + "  c-1: {command: [x]}\n", {"c-1", "already used"});
}

TEST(ComposeFile, RejectsMissingOrBadCommands) {
  expectError(demoWith("command: [climbsim-test-participant, --reads, \"a\"], ", ""), {"services.b.command", "missing"});
  expectError(demoWith("[climbsim-test-participant, --reads, \"a\"]", "[]"), {"services.b.command = []"});
  expectError(demoWith("[climbsim-test-participant, --reads, \"a\"]", "climbsim-test-participant"),
              {"services.b.command = climbsim-test-participant", "list"});
  expectError(demoWith("--reads, \"a\"]", "--name, \"a\"]"), {"services.b.command[1] = --name", "sets --name"});
  expectError(demoWith("--reads, \"a\"]", "\"--domain=3\"]"), {"services.b.command[1] = --domain=3"});
}

TEST(ComposeFile, RejectsBadClockNumbers) {
  expectError(demoWith("step_ms: 5", "step_ms: 0"), {"clock.step_ms = 0", "> 0"});
  expectError(demoWith("step_ms: 5", "step_ms: -5"), {"clock.step_ms = -5"});
  expectError(demoWith("step_ms: 5", "step_ms: .nan"), {"clock.step_ms = .nan"});
  expectError(demoWith("step_ms: 5", "step_ms: fast"), {"clock.step_ms = fast"});
  expectError(demoWith("duration_s: 10", "duration_s: .inf"), {"clock.duration_s = .inf"});
  expectError(demoWith("duration_s: 10", "duration_s: 0.001"), {"clock.duration_s = 0.001", "one step"});
  expectError(demoWith("rtf: 1.0", "rtf: -1"), {"clock.rtf = -1", ">= 0"});
  expectError(demoWith("start_timeout_s: 30", "start_timeout_s: 0"), {"clock.start_timeout_s = 0"});
  expectError(demoWith("duration_s: 10", "duration_s: 10, steps: 5"), {"clock.steps", "not both"});
  expectError(demoWith("duration_s: 10, ", ""), {"clock", "duration_s or clock.steps"});
  expectError(demoWith("duration_s: 10", "steps: 0"), {"clock.steps = 0"});
  expectError(demoWith("clock: {step_ms: 5, duration_s: 10, rtf: 1.0, start_timeout_s: 30, step_timeout_s: 10}",
                       "clock: 5"),
              {"clock = 5", "mapping"});
  // Physical ranges: what would overflow the clock's integer nanoseconds is refused here.
  expectError(demoWith("start_timeout_s: 30", "start_timeout_s: 1e308"), {"clock.start_timeout_s = 1e308", "3600"});
  expectError(demoWith("step_timeout_s: 10", "step_timeout_s: 1e20"), {"clock.step_timeout_s = 1e20"});
  expectError(demoWith("duration_s: 10", "duration_s: 1e12"), {"clock.duration_s = 1e12", "86400"});
  expectError(demoWith("duration_s: 10", "steps: 9223372036854775807"), {"clock.steps", "a day"});
  expectError(demoWith("rtf: 1.0", "rtf: 1e9"), {"clock.rtf = 1e9"});
}

TEST(ComposeFile, ReportsEveryProblemAtOnceInLineOrder) {
  // Line 1: an unknown key; line 7: an unknown key and a bad value of service b.
  const std::string message = errorOf("nmae: x\n" + demoWith("period: 2, offset: 1", "period: 0, offset: 1, colour: red"));
  std::vector<std::string> lines;
  for (std::size_t at = 0; at <= message.size();) {
    const auto end = std::min(message.find('\n', at), message.size());
    lines.push_back(message.substr(at, end - at));
    at = end + 1;
  }
  ASSERT_EQ(lines.size(), 3u) << message;
  EXPECT_NE(lines[0].find("x.yaml:1: (top level).nmae: unknown key"), std::string::npos) << message;
  EXPECT_NE(lines[1].find("x.yaml:7:"), std::string::npos) << message;
  EXPECT_NE(lines[2].find("x.yaml:7:"), std::string::npos) << message;
  EXPECT_NE(message.find("services.b.colour: unknown key"), std::string::npos) << message;
  EXPECT_NE(message.find("services.b.period = 0"), std::string::npos) << message;
}

TEST(ComposeFile, RejectsUnknownHosts) {
  expectError(demoWith("host: local", "host: robot1"),
              {"services.c.host = robot1", "unknown host", "known: local"});
  expectError(demoWith("rtf: 1.0,", "rtf: 1.0, host: nowhere,"), {"clock.host = nowhere", "unknown host"});
}

const std::string kHosts = R"(hosts:
  local:  {address: 10.77.0.1}
  second: {netns: climbsim-b, address: 10.77.0.2}
  lab:    {ssh: robot@lab-2, address: 192.168.1.12, ssh_options: [-p, "2222"]}
)";

TEST(ComposeFile, ParsesHostsOfEveryKind) {
  const ComposeFile compose = parseComposeText(kHosts + demoWith("host: local", "host: second"), "x.yaml");
  ASSERT_EQ(compose.hosts.size(), 3u);
  EXPECT_EQ(compose.hosts[0].name, "local");
  EXPECT_EQ(compose.hosts[0].kind, HostKind::local);
  EXPECT_EQ(compose.hosts[0].address, "10.77.0.1");
  EXPECT_EQ(compose.host("second").kind, HostKind::netns);
  EXPECT_EQ(compose.host("second").target, "climbsim-b");
  EXPECT_EQ(compose.host("lab").kind, HostKind::ssh);
  EXPECT_EQ(compose.host("lab").target, "robot@lab-2");
  EXPECT_EQ(compose.host("lab").ssh_options, (std::vector<std::string>{"-p", "2222"}));
  EXPECT_EQ(compose.services[2].host, "second");
  EXPECT_TRUE(compose.multiHost());
  // `lab` runs nothing: it is not a used host and needs nothing.
  const auto used = compose.usedHosts();
  ASSERT_EQ(used.size(), 2u);
  EXPECT_EQ(used[0]->name, "local");
  EXPECT_EQ(used[1]->name, "second");
}

TEST(ComposeFile, OneLocalHostIsNotMultiHost) {
  const ComposeFile compose = parseComposeText(kDemo, "x.yaml");
  ASSERT_EQ(compose.hosts.size(), 1u);
  EXPECT_FALSE(compose.multiHost());
  EXPECT_TRUE(compose.host("local").address.empty());
}

TEST(ComposeFile, RejectsBadHostEntries) {
  const std::string services = demoWith("host: local", "host: b2");
  expectError("hosts:\n  b2: {netns: a, ssh: u@h}\n" + services, {"hosts.b2", "not both"});
  expectError("hosts:\n  b2: {netns: \"a b\"}\n" + services, {"hosts.b2.netns = a b", "namespace name"});
  expectError("hosts:\n  b2: {ssh: \"u@h; rm\"}\n" + services, {"hosts.b2.ssh", "ssh destination"});
  expectError("hosts:\n  b2: {netns: n, address: 10.77.0.300}\n" + services,
              {"hosts.b2.address = 10.77.0.300", "IPv4"});
  expectError("hosts:\n  b2: {netns: n, port: 22}\n" + services, {"port"});
  expectError("hosts:\n  local: {netns: n}\n" + kDemo, {"hosts.local", "only its address"});
  expectError("hosts:\n  b2: {netns: n, ssh_options: [-p, 2]}\n" + services, {"hosts.b2.ssh_options", "only an ssh"});
  expectError("hosts:\n  b2: {ssh: u@h, ssh_options: -p}\n" + services, {"hosts.b2.ssh_options = -p", "list"});
}

TEST(ComposeFile, MultiHostNeedsDistinctAddresses) {
  const std::string services = demoWith("host: local", "host: b2");
  expectError("hosts:\n  b2: {netns: n, address: 10.77.0.2}\n" + services,
              {"hosts.local.address", "missing", "multi-host"});
  expectError("hosts:\n  local: {address: 10.77.0.1}\n  b2: {netns: n}\n" + services,
              {"hosts.b2.address", "missing"});
  expectError("hosts:\n  local: {address: 10.77.0.2}\n  b2: {netns: n, address: 10.77.0.2}\n" + services,
              {"hosts.b2.address = 10.77.0.2", "same address"});
}

TEST(ComposeFile, RejectsBadReplicas) {
  expectError(demoWith("replicas: 1", "replicas: 0"), {"services.c.replicas = 0"});
  expectError(demoWith("replicas: 1", "replicas: 1000"), {"services.c.replicas = 1000"});
}

TEST(ComposeFile, RejectsBrokenDocuments) {
  expectError("", {"empty"});
  expectError("name: [unclosed\n", {"YAML syntax error"});
  expectError("- a\n- b\n", {"mapping"});
  expectError("clock: {steps: 1}\nservices: {a: {command: [x]}}\n", {"name", "missing"});
  expectError("name: n\nservices: {a: {command: [x]}}\n", {"clock", "missing"});
  expectError("name: n\nclock: {steps: 1}\n", {"services", "missing"});
  expectError("name: n\nclock: {steps: 1}\nservices: {}\n", {"services", "at least one"});
  expectError("name: n\nclock: {steps: 1}\nservices: {a: 3}\n", {"services.a = 3", "mapping"});
}

TEST(ComposeFile, ReportsUnreadableFiles) {
  try {
    loadComposeFile("/nonexistent/compose.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/compose.yaml"), std::string::npos);
  }
}

}  // namespace
}  // namespace climbsim::launcher
