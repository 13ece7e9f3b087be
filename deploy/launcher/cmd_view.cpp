/// `view RUN_DIR`: the replay of a finished run in the browser, served by climbsim-viewer; with
/// --snapshot, a picture of the page instead (services/viewer/web/snapshot.mjs).

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"
#include "commands.hpp"

namespace climbsim::launcher {
namespace {

/// `view --snapshot PNG [--at T]`: the viewer serves the run on a free port, snapshot.mjs
/// (headless Chromium) writes the page's picture with its 3D view drawn, the viewer stops.
/// Returns snapshot.mjs's exit code (the viewer's if it ends first: a bad run directory).
int viewSnapshot(const CommandContext& context, const ViewOptions& options, std::vector<std::string> args) {
  namespace fs = std::filesystem;
  args.insert(args.end(), {"--port-tries", "100"});
  const fs::path log = fs::temp_directory_path() / ("climbsim-snapshot-" + std::to_string(::getpid()) + ".log");
  ProcessSpec spec;
  spec.argv = args;
  spec.output_file = log.string();
  ChildProcess viewer(spec);
  // The event: the viewer's line with the page's address (or its end).
  const std::regex served(R"(replay of .* at (http://\S+))");
  std::string url;
  while (url.empty()) {
    std::ifstream in(log);
    for (std::string line; url.empty() && std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, served)) url = m[1];
    }
    if (!url.empty()) break;
    if (const auto code = viewer.waitFor(std::chrono::milliseconds(100))) {
      std::ifstream lines(log);
      for (std::string line; std::getline(lines, line);) {
        if (!line.empty()) std::fprintf(stderr, "%s\n", line.c_str());
      }
      fs::remove(log);
      return *code;
    }
  }
  ProcessSpec shot;
  shot.argv = {"node", context.root + "/services/viewer/web/snapshot.mjs", "--url", url, "--out", options.snapshot,
               "--modules", context.build_dir + "/viewer/npm/node_modules"};
  if (options.at_s) shot.argv.insert(shot.argv.end(), {"--at", std::to_string(*options.at_s)});
  ChildProcess snapshot(shot);
  std::optional<int> code;
  while (!(code = snapshot.waitFor(std::chrono::seconds(1)))) {
  }
  viewer.signal(SIGTERM);
  viewer.waitFor(std::chrono::seconds(10));
  fs::remove(log);
  return *code;
}

}  // namespace

int commandView(const CommandContext& context, const ViewOptions& options) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(options.run_dir).lexically_normal();
  if (!fs::is_directory(dir)) throw ConfigError(options.run_dir + ": no such run directory");
  for (const char* needed : {"trace.csv", "scenario.yaml"}) {
    if (!fs::exists(dir / needed)) {
      throw ConfigError((dir / needed).string() + ": missing: not a run directory (made by 'run' or 'up')");
    }
  }
  const std::string program = context.build_dir + "/bin/climbsim-viewer";
  if (::access(program.c_str(), X_OK) != 0) throw ConfigError(program + ": not built (climbsim build)");
  std::vector<std::string> args = {program, "--replay", dir.string(), "--port", std::to_string(options.port),
                                   "--bind", options.bind};
  if (!options.snapshot.empty()) return viewSnapshot(context, options, args);
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  // The viewer takes over this process: its exit code (2 for a port in use) is view's.
  ::execv(program.c_str(), argv.data());
  spdlog::error("cannot run {}", program);
  return 1;
}

}  // namespace climbsim::launcher
