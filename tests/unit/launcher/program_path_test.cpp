// Where a compose file's programs are found (launch_plan.hpp resolveExecutable): a bare name in
// <build>/bin, then on PATH; a relative path from the compose file's own folder, also when
// that file lives outside the repository (a controller example copied out of it); a program
// that is not there is one line naming the compose file, the service, the path as written and
// as resolved.

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"
#include "compose_file.hpp"
#include "launch_plan.hpp"

namespace fs = std::filesystem;
using namespace climbsim;
using namespace climbsim::launcher;

namespace {

class ProgramPathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/climbsim-program-path-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    top_ = pattern;
    // A build directory of the repository and, elsewhere, a user's folder with a compose file.
    makeProgram("repo/build/bin/climbsim-clock");
    makeProgram("repo/build/bin/climbsim-python");
    makeProgram("elsewhere/ctl/tools/my-tool");
    fs::create_directories(top_ + "/elsewhere/ctl/cwd");
  }
  void TearDown() override { fs::remove_all(top_); }

  void makeProgram(const std::string& relative) {
    const fs::path path = fs::path(top_) / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "#!/bin/sh\n";
    ::chmod(path.c_str(), 0755);
  }

  /// Writes `text` as elsewhere/ctl/compose.yaml and loads it.
  ComposeFile userCompose(const std::string& text) {
    std::ofstream(composePath()) << text;
    return loadComposeFile(composePath());
  }
  std::string composePath() const { return top_ + "/elsewhere/ctl/compose.yaml"; }
  ExecutableSearch search() const { return executableSearch(composePath(), top_ + "/repo/build", "/nonexistent"); }

  std::string top_;
};

/// The program (argv[0]) of the plan's process `name`.
std::string programOf(const LaunchPlan& plan, const std::string& name) {
  for (const auto& process : plan.processes) {
    if (process.name == name) return process.argv.front();
  }
  ADD_FAILURE() << "no process " << name;
  return "";
}

TEST_F(ProgramPathTest, ARelativePathIsTakenFromTheComposeFilesFolderOutsideTheRepository) {
  const ComposeFile compose = userCompose(R"(name: mine
clock: {steps: 10}
services:
  tool: {command: [tools/my-tool, --x]}
  dot: {command: [./tools/my-tool]}
  python: {command: [climbsim-python, my_controller.py]}
)");
  // Whatever the launcher's working directory is.
  struct WorkingDirectory {
    fs::path before = fs::current_path();
    explicit WorkingDirectory(const fs::path& dir) { fs::current_path(dir); }
    ~WorkingDirectory() { fs::current_path(before); }
  };
  const LaunchPlan plan = [&] {
    const WorkingDirectory cwd(top_ + "/elsewhere/ctl/cwd");
    return buildLaunchPlan(compose, 5, search());
  }();
  EXPECT_EQ(programOf(plan, "tool"), top_ + "/elsewhere/ctl/tools/my-tool");
  EXPECT_EQ(programOf(plan, "dot"), top_ + "/elsewhere/ctl/tools/my-tool");
  EXPECT_EQ(programOf(plan, "python"), top_ + "/repo/build/bin/climbsim-python") << "a bare name: the build's";
  EXPECT_EQ(programOf(plan, "clock"), top_ + "/repo/build/bin/climbsim-clock");
}

TEST_F(ProgramPathTest, AMissingProgramIsOneLineWithTheFileTheServiceAndBothPaths) {
  const ComposeFile compose = userCompose(R"(name: mine
clock: {steps: 10}
services:
  ctl: {command: [build/bin/climbsim-python, my_controller.py]}
)");
  try {
    buildLaunchPlan(compose, 5, search());
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind(composePath() + ":4: services.ctl.command[0] = build/bin/climbsim-python: '", 0), 0u)
        << what;
    EXPECT_NE(what.find("'" + top_ + "/elsewhere/ctl/build/bin/climbsim-python' does not exist"), std::string::npos)
        << what;
    EXPECT_NE(what.find("compose file's folder"), std::string::npos) << what;
    EXPECT_NE(what.find("named alone: climbsim-python (found in " + top_ + "/repo/build/bin)"), std::string::npos)
        << what;
  }
}

TEST_F(ProgramPathTest, AFileThatIsNotExecutableIsNamedAsSuch) {
  std::ofstream(top_ + "/elsewhere/ctl/tools/plain") << "text\n";
  const ComposeFile compose = userCompose("name: mine\nclock: {steps: 10}\nservices:\n  p: {command: [tools/plain]}\n");
  try {
    buildLaunchPlan(compose, 5, search());
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("services.p.command[0] = tools/plain: '" + top_ + "/elsewhere/ctl/tools/plain' is not an "
                        "executable file"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("named alone"), std::string::npos) << "no such program in the build: " << what;
  }
}

TEST(ShippedComposeFiles, NameEveryProgramAloneSoThatItComesFromTheBuild) {
  // Every compose file of the repository names its programs without a folder: they come from
  // <build>/bin (then PATH), wherever the compose file is.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(CLIMBSIM_ROOT) / "deploy")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("compose", 0) != 0 || entry.path().extension() != ".yaml") continue;
    ++files;
    const ComposeFile compose = loadComposeFile(entry.path().string());
    for (const auto& service : compose.services) {
      EXPECT_EQ(service.command.front().find('/'), std::string::npos) << name << ": " << service.name;
    }
  }
  EXPECT_GE(files, 5);
}

}  // namespace
