#pragma once
// Helpers of the system tests: run the launcher as a user does and read what a run wrote.

#include <sys/wait.h>

#include <algorithm>
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

/// Complete rows of a trace (lines after the header with as many cells as the header).
inline std::size_t completeRows(const fs::path& trace, bool* all_complete = nullptr) {
  std::istringstream lines(readFile(trace));
  std::string header;
  if (!std::getline(lines, header)) return 0;
  const auto cells = [](const std::string& line) { return std::count(line.begin(), line.end(), ','); };
  std::size_t rows = 0;
  bool complete = true;
  for (std::string line; std::getline(lines, line);) {
    if (cells(line) == cells(header)) {
      ++rows;
    } else {
      complete = false;
    }
  }
  if (all_complete != nullptr) *all_complete = complete;
  return rows;
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

/// `<bin>/<program> <args> --out <runs>/<tag>` with its output in <runs>/<tag>.log, to its end.
inline RunResult runTool(const std::string& program, const std::string& tag, const std::string& args) {
  RunResult r;
  r.dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / tag;
  fs::remove_all(r.dir);
  fs::create_directories(r.dir.parent_path());
  const std::string log = r.dir.string() + ".log";
  const std::string command = std::string(CLIMBSIM_BIN_DIR) + "/" + program + " " + args + " --out " + r.dir.string() +
                              " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = readFile(log);
  return r;
}

inline std::size_t lineCount(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace climbsim::system_test
