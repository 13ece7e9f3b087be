#include "launch_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <stdlib.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

class LaunchPlanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/climbsim-plan-test-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    root_ = pattern;
    fs::create_directories(root_ + "/bin");
    fs::create_directories(root_ + "/path");
    fs::create_directories(root_ + "/deploy/tools");
    makeProgram("bin/climbsim-clock");
    makeProgram("bin/climbsim-test-participant");
    makeProgram("path/climbsim-test-participant");
    makeProgram("path/other-tool");
    makeProgram("deploy/tools/local-tool");
    search_ = ExecutableSearch{root_ + "/bin", root_ + "/deploy", "/nonexistent:" + root_ + "/path"};
  }
  void TearDown() override { fs::remove_all(root_); }

  void makeProgram(const std::string& relative) {
    const std::string path = root_ + "/" + relative;
    std::ofstream(path) << "#!/bin/sh\n";
    ::chmod(path.c_str(), 0755);
  }

  std::string root_;
  ExecutableSearch search_;
};

ComposeFile demo() {
  return parseComposeText(R"(name: demo
clock: {step_ms: 5, duration_s: 10, rtf: 1.0, start_timeout_s: 30, step_timeout_s: 10}
services:
  a: {command: [climbsim-test-participant, --reads, "b,c"], period: 1, offset: 0}
  b: {command: [other-tool], period: 2, offset: 1}
  c: {command: [./tools/local-tool, -x], period: 4, offset: 3, replicas: 2}
)",
                          "demo.yaml");
}

TEST_F(LaunchPlanTest, BuildsTheClockWithTheRoster) {
  const LaunchPlan plan = buildLaunchPlan(demo(), 42, search_);
  EXPECT_EQ(plan.domain_id, 42);
  ASSERT_EQ(plan.processes.size(), 5u);
  EXPECT_EQ(plan.processes[0].name, "clock");
  EXPECT_EQ(plan.processes[0].argv,
            (std::vector<std::string>{root_ + "/bin/climbsim-clock", "--roster", "a,b,c-0,c-1", "--step-ms", "5",
                                      "--duration-s", "10", "--rtf", "1", "--start-timeout-s", "30",
                                      "--step-timeout-s", "10", "--domain", "42", "--control-from",
                                      controlSenders(demo())}));
}

TEST_F(LaunchPlanTest, ClockControlIsForTheListedSendersAndTheirHosts) {
  makeProgram("bin/climbsim-viewer");
  // Default: climbsim-clockctl from this machine, the viewer from its host.
  const ComposeFile defaults = parseComposeText(R"(name: demo
clock: {step_ms: 5, duration_s: 10}
services:
  a: {command: [climbsim-test-participant]}
  viewer: {command: [climbsim-viewer, --port, "8765"], observer: true}
)",
                                                "demo.yaml");
  const std::string text = controlSenders(defaults);
  EXPECT_EQ(text.rfind("climbsim-clockctl@", 0), 0u) << text;
  EXPECT_NE(text.find("127.0.0.1"), std::string::npos) << text;
  EXPECT_NE(text.find(",viewer@"), std::string::npos) << text;
  EXPECT_EQ(buildLaunchPlan(defaults, 9, search_).processes[0].argv.back(), text);

  // Listed: named hosts become their addresses, a bare name may send from anywhere.
  const ComposeFile listed = parseComposeText(R"(name: two
hosts:
  second: {netns: climbsim-b, address: 10.77.0.2}
clock: {duration_s: 1, max_pause_s: 30, control: [climbsim-clockctl@second, my-tool]}
services:
  a: {command: [climbsim-test-participant]}
)",
                                              "two.yaml");
  EXPECT_EQ(controlSenders(listed), "climbsim-clockctl@10.77.0.2,my-tool");
  const auto argv = buildLaunchPlan(listed, 9, search_).processes[0].argv;
  const auto pause = std::find(argv.begin(), argv.end(), "--max-pause-s");
  ASSERT_NE(pause, argv.end());
  EXPECT_EQ(*(pause + 1), "30");
  EXPECT_EQ(controlSenders(parseComposeText("name: n\nclock: {steps: 1, control: []}\nservices: {s: {command: [x]}}\n",
                                            "x.yaml")),
            "")
      << "an empty list: nobody may";

  try {
    parseComposeText("name: n\nclock: {steps: 1, control: [clockctl@mars]}\nservices: {s: {command: [x]}}\n", "x.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("clock.control[0]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown host"), std::string::npos) << e.what();
  }
}

TEST_F(LaunchPlanTest, ObserversGetOnlyNameAndDomain) {
  makeProgram("bin/climbsim-viewer");
  const ComposeFile compose = parseComposeText(R"(name: demo
clock: {step_ms: 5, duration_s: 10}
services:
  a: {command: [climbsim-test-participant]}
  viewer: {command: [climbsim-viewer, --port, "8765"], observer: true}
)",
                                               "demo.yaml");
  const LaunchPlan plan = buildLaunchPlan(compose, 9, search_);
  ASSERT_EQ(plan.processes.size(), 3u);
  EXPECT_EQ(plan.processes[0].argv[2], "a");  // the roster
  EXPECT_EQ(plan.processes[2].argv, (std::vector<std::string>{root_ + "/bin/climbsim-viewer", "--port", "8765",
                                                              "--name", "viewer", "--domain", "9"}));
}

TEST_F(LaunchPlanTest, AppendsTheLauncherOptionsToEveryService) {
  const LaunchPlan plan = buildLaunchPlan(demo(), 7, search_);
  EXPECT_EQ(plan.processes[1].argv,
            (std::vector<std::string>{root_ + "/bin/climbsim-test-participant", "--reads", "b,c", "--name", "a",
                                      "--period", "1", "--offset", "0", "--domain", "7"}));
  EXPECT_EQ(plan.processes[2].argv,
            (std::vector<std::string>{root_ + "/path/other-tool", "--name", "b", "--period", "2", "--offset", "1",
                                      "--domain", "7"}));
  EXPECT_EQ(plan.processes[3].name, "c-0");
  EXPECT_EQ(plan.processes[4].argv,
            (std::vector<std::string>{root_ + "/deploy/tools/local-tool", "-x", "--name", "c-1", "--period", "4",
                                      "--offset", "3", "--domain", "7"}));
}

TEST_F(LaunchPlanTest, StepsAndStartPausedReachTheClock) {
  const auto compose = parseComposeText(
      "name: n\nclock: {steps: 20, step_ms: 0.1, start_paused: true}\nservices: {s: {command: [other-tool]}}\n",
      "x.yaml");
  const auto argv = buildLaunchPlan(compose, 1, search_).processes[0].argv;
  const std::vector<std::string> expected{root_ + "/bin/climbsim-clock", "--roster", "s", "--step-ms", "0.1",
                                          "--steps", "20", "--rtf", "0", "--start-timeout-s", "30",
                                          "--step-timeout-s", "10", "--start-paused", "--domain", "1",
                                          "--control-from", controlSenders(compose)};
  EXPECT_EQ(argv, expected);
}

TEST_F(LaunchPlanTest, NamesAMissingProgram) {
  const auto compose = parseComposeText("name: n\nclock: {steps: 1}\nservices:\n  s: {command: [no-such-tool]}\n",
                                        "x.yaml");
  try {
    buildLaunchPlan(compose, 1, search_);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("x.yaml:4: services.s.command[0] = no-such-tool"), std::string::npos) << message;
  }
}

TEST_F(LaunchPlanTest, NeedsTheClockProgram) {
  fs::remove(root_ + "/bin/climbsim-clock");
  EXPECT_THROW(buildLaunchPlan(demo(), 1, search_), ConfigError);
}

TEST_F(LaunchPlanTest, ScenarioTokensAndRatePeriods) {
  const auto compose = parseComposeText(R"(name: n
scenario: scenarios/s.yaml
clock: {rtf: 0}
services:
  sealing: {command: [other-tool, --scenario, "${scenario}", --shard, "${replica}/${replicas}"], period: depth, offset: 1, replicas: 2}
  rec: {command: [other-tool, "--out=${out}"]}
)",
                                        "/c/compose.yaml");
  EXPECT_EQ(compose.scenario, "/c/scenarios/s.yaml");
  ScenarioRun run;
  run.scenario_file = "/r/scenario.yaml";
  run.out_dir = "/r";
  run.step_ms = 2.5;
  run.duration_s = 7;
  run.depth_period = 8;
  const auto plan = buildLaunchPlan(compose, 3, search_, run);
  ASSERT_EQ(plan.processes.size(), 4u);
  EXPECT_EQ(plan.processes[0].argv[4], "2.5");
  EXPECT_EQ(plan.processes[0].argv[5], "--duration-s");
  EXPECT_EQ(plan.processes[0].argv[6], "7");
  EXPECT_EQ(plan.processes[2].argv,
            (std::vector<std::string>{root_ + "/path/other-tool", "--scenario", "/r/scenario.yaml", "--shard", "1/2",
                                      "--name", "sealing-1", "--period", "8", "--offset", "1", "--domain", "3"}));
  EXPECT_EQ(plan.processes[3].argv[1], "--out=/r");

  // Without a scenario the tokens and the rate-named period cannot be resolved.
  EXPECT_THROW(buildLaunchPlan(compose, 3, search_), ConfigError);
  run.depth_period = 1;  // offset 1 is not below the period 1
  try {
    buildLaunchPlan(compose, 3, search_, run);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("services.sealing.offset = 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseComposeText("name: n\nclock: {steps: 1}\nservices: {s: {command: [a, \"${nope}\"]}}\n", "x.yaml"),
               ConfigError);
}

TEST_F(LaunchPlanTest, PlacesProcessesOnTheirHostsWithUnicastDiscovery) {
  const ComposeFile compose = parseComposeText(R"(name: two
hosts:
  local:  {address: 10.77.0.1}
  second: {netns: climbsim-b, address: 10.77.0.2}
  lab:    {ssh: robot@lab-2, address: 10.77.0.3, ssh_options: [-F, /etc/x]}
clock: {duration_s: 1}
services:
  a: {command: [climbsim-test-participant, --reads, "b it's"]}
  b: {command: [climbsim-test-participant], replicas: 2, host: second}
  c: {command: [climbsim-test-participant], host: lab}
)",
                                               "two.yaml");
  const LaunchPlan plan = buildLaunchPlan(compose, 9, search_);
  ASSERT_EQ(plan.processes.size(), 5u);
  const std::map<std::string, std::string> env_here = {{"CLIMBSIM_DDS_PEERS", "10.77.0.1,10.77.0.2,10.77.0.3"},
                                                       {"CLIMBSIM_DDS_INTERFACE", "10.77.0.1"},
                                                       {"CLIMBSIM_DDS_PEER_RANGE", "10"}};
  EXPECT_EQ(plan.processes[0].host, "local");
  EXPECT_EQ(plan.processes[0].env, env_here);
  EXPECT_EQ(plan.processes[0].argv.front(), root_ + "/bin/climbsim-clock");
  EXPECT_EQ(plan.processes[1].env, env_here);
  // netns: the program behind `ip netns exec`, the environment from the launcher.
  const auto& b0 = plan.processes[2];
  EXPECT_EQ(b0.host, "second");
  EXPECT_EQ(b0.env.at("CLIMBSIM_DDS_INTERFACE"), "10.77.0.2");
  EXPECT_EQ(b0.argv, (std::vector<std::string>{"ip", "netns", "exec", "climbsim-b",
                                               root_ + "/bin/climbsim-test-participant", "--name", "b-0",
                                               "--period", "1", "--offset", "0", "--domain", "9"}));
  // ssh: one quoted remote command carrying the environment.
  const auto& c = plan.processes[4];
  ASSERT_EQ(c.argv.size(), 11u);
  EXPECT_EQ(c.argv[0], "ssh");
  EXPECT_EQ(c.argv[1], "-tt");
  EXPECT_EQ(c.argv[6], "-F");
  EXPECT_EQ(c.argv[7], "/etc/x");
  EXPECT_EQ(c.argv[8], "robot@lab-2");
  EXPECT_EQ(c.argv[10], "exec env 'CLIMBSIM_DDS_INTERFACE=10.77.0.3' 'CLIMBSIM_DDS_PEERS=10.77.0.1,10.77.0.2,10.77.0.3' "
                       "'CLIMBSIM_DDS_PEER_RANGE=10' '" + root_ + "/bin/climbsim-test-participant' '--name' 'c' "
                       "'--period' '1' '--offset' '0' '--domain' '9'");
}

TEST_F(LaunchPlanTest, OneHostHasNoDiscoveryEnvironment) {
  const LaunchPlan plan = buildLaunchPlan(demo(), 7, search_);
  for (const auto& process : plan.processes) {
    EXPECT_TRUE(process.env.empty()) << process.name;
    EXPECT_EQ(process.host, "local");
  }
}

TEST(ShellQuoted, SurvivesQuotesAndSpaces) {
  EXPECT_EQ(shellQuoted("plain"), "'plain'");
  EXPECT_EQ(shellQuoted("b it's"), "'b it'\\''s'");
}

TEST(CheckHosts, NamesAMissingNamespace) {
  const ComposeFile compose = parseComposeText(R"(name: two
hosts:
  local: {address: 10.77.0.1}
  second: {netns: climbsim-no-such-namespace, address: 10.77.0.2}
clock: {duration_s: 1}
services:
  b: {command: [x], host: second}
)",
                                               "two.yaml");
  try {
    checkHosts(compose, "/usr/sbin:/usr/bin:/sbin:/bin");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("two.yaml:4: hosts.second.netns = climbsim-no-such-namespace"),
              std::string::npos)
        << e.what();
  }
}

TEST(FormatNumber, IsShortAndExact) {
  EXPECT_EQ(formatNumber(5.0), "5");
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(2.5), "2.5");
  EXPECT_EQ(std::stod(formatNumber(1.0 / 3.0)), 1.0 / 3.0);
}

}  // namespace
}  // namespace climbsim::launcher
