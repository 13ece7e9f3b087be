#include "run_state.hpp"

#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <stdexcept>

namespace climbsim::launcher {
namespace {

TEST(RunState, RoundTripsThroughAFile) {
  char pattern[] = "/tmp/climbsim-state-test-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const std::string path = std::string(pattern) + "/state.json";
  RunState state;
  state.compose_name = "demo";
  state.compose_file = "/r/deploy/compose.yaml";
  state.run_dir = "/b/run/demo";
  state.supervisor_pid = 123;
  state.detached = true;
  state.domain_id = 42;
  state.started_at = "2024-01-02T03:04:05";
  state.viewer_url = "http://127.0.0.1:8766/";
  state.processes = {{"clock", 124, 0}, {"a", 125, std::nullopt}};
  writeRunState(path, state);
  const auto read = readRunState(path);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->compose_name, "demo");
  EXPECT_EQ(read->supervisor_pid, 123);
  EXPECT_TRUE(read->detached);
  EXPECT_EQ(read->domain_id, 42);
  EXPECT_EQ(read->viewer_url, "http://127.0.0.1:8766/");
  ASSERT_EQ(read->processes.size(), 2u);
  EXPECT_EQ(read->processes[0].exit_code, 0);
  EXPECT_FALSE(read->processes[1].exit_code);
  EXPECT_FALSE(read->exit_code);
  std::filesystem::remove_all(pattern);
  EXPECT_FALSE(readRunState(path));
}

TEST(RunState, RejectsMalformedText) {
  EXPECT_THROW(runStateFromJson("{\"compose_name\": 3}", "s.json"), std::runtime_error);
  EXPECT_THROW(runStateFromJson("not json", "s.json"), std::runtime_error);
}

TEST(RunPaths, LiveUnderTheBuildDirectory) {
  const RunPaths paths("/b/", "demo");
  EXPECT_EQ(paths.dir, "/b/run/demo");
  EXPECT_EQ(paths.logFile("clock"), "/b/run/demo/logs/clock.log");
  EXPECT_EQ(paths.state_file, "/b/run/demo/state.json");
}

}  // namespace
}  // namespace climbsim::launcher
