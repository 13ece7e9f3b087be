// climbsim-surface as a user runs it: good specs write meshes, bad ones exit 2 with one
// line naming the file or option, the key and the value.

#include <gtest/gtest.h>

#include <algorithm>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>

#include "surface_sampler.hpp"

#ifndef CLIMBSIM_SURFACE_EXE
#error "CLIMBSIM_SURFACE_EXE must name the climbsim-surface executable"
#endif

namespace climbsim::surface {
namespace {

struct CliRun {
  int code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& arguments) {
  CliRun result;
  const std::string command = std::string(CLIMBSIM_SURFACE_EXE) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int status = pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string writeSpec(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

int lineCount(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

TEST(SurfaceCli, WritesAPatchFromASpecAndOptionsDeterministically) {
  const test::ScopedTempDir dir_scope("cli_good");
  const std::string& dir = dir_scope.path;
  const std::string spec = writeSpec(dir, "spec.yaml",
                                     "size_m: 0.4\ngrid_m: 0.005\nseed: 9\n"
                                     "rough: {rms_m: 0.001, correlation_length_m: 0.02}\n"
                                     "cracks:\n  - {x_m: 0.2, y_m: 0.1, width_m: 0.006, depth_m: 0.02, profile: v}\n");
  const std::string options = " --hole x_m=0.2,y_m=0.3,diameter_m=0.04,depth_m=0.02 --step x_m=0.1,y_m=0.2,height_m=0.005";
  const CliRun a = run("patch --spec " + spec + " --out " + dir + "/a.ply" + options);
  const CliRun b = run("patch --spec " + spec + " --out " + dir + "/b.ply" + options);
  ASSERT_EQ(a.code, 0) << a.output;
  ASSERT_EQ(b.code, 0) << b.output;
  EXPECT_TRUE(test::readBytes(dir + "/a.ply") == test::readBytes(dir + "/b.ply"));
  const CliRun c = run("patch --spec " + spec + " --seed 10 --out " + dir + "/c.ply" + options);
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_FALSE(test::readBytes(dir + "/a.ply") == test::readBytes(dir + "/c.ply"));
}

struct BadCase {
  const char* spec;     // YAML text, or "" for none
  const char* options;  // extra command-line options
  const char* expect1;  // substrings of the error line
  const char* expect2;
};

class SurfaceCliBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SurfaceCliBadInput, ExitsTwoWithOneLineNamingKeyAndValue) {
  const BadCase c = GetParam();
  const test::ScopedTempDir dir_scope("cli_bad");
  const std::string& dir = dir_scope.path;
  std::string arguments = "patch ";
  if (std::string(c.options).find("--out") == std::string::npos) arguments += "--out " + dir + "/x.ply ";
  if (*c.spec) arguments += "--spec " + writeSpec(dir, "bad.yaml", c.spec) + " ";
  arguments += c.options;
  const CliRun r = run(arguments);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(c.expect1), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(c.expect2), std::string::npos) << r.output;
  EXPECT_EQ(lineCount(r.output), 1) << r.output;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SurfaceCliBadInput,
    ::testing::Values(
        BadCase{"cracks:\n  - {x_m: 1, y_m: 1, width_m: -0.01, depth_m: 0.02}\n", "", "bad.yaml:2",
                "cracks[0].width_m = -0.01"},
        BadCase{"rough: {rms_m: 0.001, corelation_length_m: 0.02}\n", "", "bad.yaml:1",
                "rough.corelation_length_m: unknown key"},
        BadCase{"holes:\n  - {x_m: 0.01, y_m: 1, diameter_m: 0.05, depth_m: 0.02}\n", "", "holes[0].x_m = 0.01",
                "inside the face"},
        BadCase{"grid_m: fine\n", "", "bad.yaml:1", "grid_m = fine: it must be a finite number"},
        BadCase{"seed: -3\n", "", "bad.yaml:1", "seed = -3"},
        BadCase{"cracks: {x_m: 1}\n", "", "bad.yaml:1", "cracks"},
        BadCase{"crack_network: {count: 2, profile: w}\n", "", "crack_network.profile = w", "rect, v or u"},
        BadCase{"size_m: [1, 2\n", "", "bad.yaml", "YAML syntax"},
        BadCase{"", "--crack width_m=abc", "--crack", "cracks[0].width_m = abc"},
        BadCase{"", "--hole x_m=1,y_m", "--hole", "expected key=value"},
        BadCase{"", "--groove x_m=1,y_m=1,depth_m=2", "grooves[0].depth_m = 2", "size_m / 2"},
        BadCase{"", "--grid 0", "--grid", "grid_m = 0"},
        BadCase{"", "--out /tmp/x.xyz", "/tmp/x.xyz", "unknown mesh extension"}),
    // Named by index: the default name prints the case's bytes, which differ between builds.
    [](const ::testing::TestParamInfo<BadCase>& info) { return "case" + std::to_string(info.index); });

TEST(SurfaceCli, EveryProblemOfASpecIsReportedAtOnceInLineOrder) {
  const test::ScopedTempDir dir_scope("cli_many");
  const std::string& dir = dir_scope.path;
  const std::string spec = writeSpec(dir, "many.yaml",
                                     "size_m: 2\n"
                                     "seed: -3\n"
                                     "rough: {rms_m: x}\n"
                                     "cracks:\n"
                                     "  - {x_m: 1, widht_m: 0.01}\n"
                                     "crack_network: {count: 2, profile: w}\n");
  const CliRun r = run("patch --out " + dir + "/x.ply --spec " + spec);
  EXPECT_EQ(r.code, 2) << r.output;
  std::vector<std::size_t> at;
  for (const char* part : {"many.yaml:2: seed = -3", "many.yaml:3: rough.rms_m = x", "many.yaml:5: cracks[0].widht_m: unknown key",
                           "many.yaml:6: crack_network.profile = w"}) {
    at.push_back(r.output.find(part));
    EXPECT_NE(at.back(), std::string::npos) << part << " in " << r.output;
  }
  EXPECT_TRUE(std::is_sorted(at.begin(), at.end())) << r.output;
  EXPECT_EQ(lineCount(r.output), 4) << r.output;
}

TEST(SurfaceCli, MissingSpecFileExitsTwo) {
  const CliRun r = run("patch --spec /nonexistent/spec.yaml");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/spec.yaml"), std::string::npos) << r.output;
}

TEST(SurfaceCli, HelpDocumentsTheSpecKeys) {
  const CliRun r = run("patch --help");
  EXPECT_EQ(r.code, 0);
  for (const char* key : {"correlation_length_m", "crack_network", "holes", "steps", "grooves", "--crack", "exit code 2"})
    EXPECT_NE(r.output.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace climbsim::surface
