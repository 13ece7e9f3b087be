#include "run_registry.hpp"

#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>

#include "climbsim/errors.hpp"

namespace climbsim::launcher {
namespace {

class RunRegistry : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/climbsim-registry-test-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    build_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(build_); }

  /// A finished run `name` started at `started_at`.
  void finishedRun(const std::string& name, const std::string& started_at) {
    const RunPaths paths(build_, name);
    std::filesystem::create_directories(paths.dir);
    RunState state;
    state.name = name;
    state.compose_name = "climbsim";
    state.compose_file = "/r/deploy/compose.yaml";
    state.started_at = started_at;
    state.exit_code = 0;
    writeRunState(paths.state_file, state);
  }

  std::string build_;
};

TEST_F(RunRegistry, ADefaultNameIsMadeUniqueAmongRunningRuns) {
  auto first = claimRun(build_, "crack-descent", false);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->name, "crack-descent");
  auto second = claimRun(build_, "crack-descent", false);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->name, "crack-descent-2");
  EXPECT_EQ(second->paths.dir, build_ + "/run/crack-descent-2");
  // An explicit name is that name or nothing.
  EXPECT_FALSE(claimRun(build_, "crack-descent", true));
  // A finished run's name is free again.
  first.reset();
  auto third = claimRun(build_, "crack-descent", false);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->name, "crack-descent");
}

TEST_F(RunRegistry, BaseNamesAreDirectoryNames) {
  EXPECT_EQ(baseRunName("crack descent/1"), "crack-descent-1");
  EXPECT_EQ(baseRunName(".."), "run");
  EXPECT_EQ(baseRunName(std::string(200, 'a')).size(), 59u);
  EXPECT_THROW(validateRunName("a/b"), ConfigError);
  EXPECT_THROW(validateRunName(".."), ConfigError);
  EXPECT_THROW(validateRunName(std::string(64, 'a')), ConfigError);
  EXPECT_NO_THROW(validateRunName("my-run.2"));
}

TEST_F(RunRegistry, SelectsTheOnlyRunningRunOrTheNamedOne) {
  finishedRun("old", "2024-01-01T00:00:00");
  finishedRun("newer", "2024-01-02T00:00:00");
  // Nothing running: the last one (for logs and ps), none for down.
  EXPECT_EQ(selectRun(build_, "", "", true)->name, "newer");
  EXPECT_FALSE(selectRun(build_, "", "", false));
  EXPECT_EQ(selectRun(build_, "old", "", false)->name, "old");
  auto a = claimRun(build_, "a", true);
  ASSERT_TRUE(a);
  EXPECT_EQ(selectRun(build_, "", "", false)->name, "a");
  auto b = claimRun(build_, "b", true);
  try {
    selectRun(build_, "", "", false);
    FAIL() << "two running runs are ambiguous";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "2 runs are running (a, b): name one");
  }
  try {
    selectRun(build_, "nope", "", false);
    FAIL() << "an unknown name is an error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("no run named 'nope'"), std::string::npos) << e.what();
  }
  // -f keeps the runs of that compose file only.
  EXPECT_EQ(selectRun(build_, "", "/r/deploy/compose.yaml", true)->name, "newer");
  const auto runs = listRuns(build_);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_TRUE(runs[0].running);
  EXPECT_TRUE(runs[1].running);
  EXPECT_EQ(runs[2].name, "newer");
}

}  // namespace
}  // namespace climbsim::launcher
