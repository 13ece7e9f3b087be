/// `view RUN_DIR`: the replay of a finished run in the browser, served by climbsim-viewer.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "climbsim/errors.hpp"
#include "commands.hpp"

namespace climbsim::launcher {

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
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  // The viewer takes over this process: its exit code (2 for a port in use) is view's.
  ::execv(program.c_str(), argv.data());
  spdlog::error("cannot run {}", program);
  return 1;
}

}  // namespace climbsim::launcher
