#pragma once
// Helpers of the system tests: run the launcher as a user does and read what a run wrote.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace climbsim::system_test {

namespace fs = std::filesystem;

inline std::string readFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream out;
  out << in.rdbuf();
  return out.str();
}

/// The launcher's command line: `climbsim-compose run <args> --out <out>`.
inline std::string launcherCommand(const std::string& args, const fs::path& out) {
  return std::string(CLIMBSIM_BIN_DIR) + "/climbsim-compose --root " + CLIMBSIM_ROOT + " --build " +
         CLIMBSIM_BUILD_DIR + " run " + args + " --out " + out.string();
}

struct RunResult {
  int exit_code = -1;
  std::string output;  ///< the launcher's stdout and stderr
  fs::path dir;        ///< the run directory
};

/// `climbsim-compose run <args> --out <runs>/<tag>`, to its end.
inline RunResult runScenario(const std::string& tag, const std::string& args) {
  RunResult r;
  r.dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / tag;
  fs::remove_all(r.dir);
  fs::create_directories(r.dir.parent_path());
  const std::string log = r.dir.string() + ".log";
  const int status = std::system((launcherCommand(args, r.dir) + " > " + log + " 2>&1").c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = readFile(log);
  return r;
}

}  // namespace climbsim::system_test
