// `climbsim-robot show`: draws every shipped robot (the pictures docs/robot-files.md shows are
// the ones it draws today), and a bad file is every problem listed, exit code 2.

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Result {
  int exit_code = -1;
  std::string output;
};

Result run(const std::string& args) {
  Result r;
  const std::string command = std::string(CLIMBSIM_ROBOT_PROGRAM) + " " + args + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) r.output += buffer;
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RobotShow, EveryShippedRobotIsDrawnAsTheDocsShowIt) {
  for (const char* name : {"cromsci", "single-chamber", "grid-2x2", "ring-12"}) {
    SCOPED_TRACE(name);
    const std::string out = testing::TempDir() + "climbsim_robot_show_" + name + ".png";
    const Result r = run(std::string("show ") + name + " --width 900 --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string drawn = bytesOf(out);
    ASSERT_GT(drawn.size(), 1000u);
    EXPECT_EQ(drawn.substr(1, 3), "PNG");
    // The committed picture is the one the tool draws (regenerate: the command in docs/robot-files.md).
    EXPECT_TRUE(drawn == bytesOf(std::string(CLIMBSIM_DOC_DIR) + "/robot-file-" + name + ".png"))
        << "deploy/doc/robot-file-" << name << ".png is stale: climbsim-robot show " << name
        << " --width 900 --out deploy/doc/robot-file-" << name << ".png";
  }
}

TEST(RobotShow, ABadFileListsEveryProblemAndExitsTwo) {
  const std::string file = testing::TempDir() + "climbsim_robot_show_bad.yaml";
  std::ofstream(file) << "name: bad\nbody: {diameter_m: -1, mass_kg: 10, com_height_m: 0.1}\n"
                         "chambers: {layout: hexagon}\n";
  const Result r = run("show " + file + " --out " + testing::TempDir() + "climbsim_robot_show_bad.png");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(file + ":2: body.diameter_m = -1: must be in (0, 10]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(file + ":3: chambers.layout = hexagon: must be one of ring, grid, single, polygons"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(file + ":1: sealing: missing"), std::string::npos) << r.output;
  const Result missing = run("show no-such-robot --out " + testing::TempDir() + "x.png");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("no-such-robot.yaml: cannot read the robot description"), std::string::npos)
      << missing.output;
}

}  // namespace
