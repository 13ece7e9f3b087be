#include "climbsim/main_guard.hpp"

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/logging.hpp"

namespace climbsim {

int guardedMain(CLI::App& app, int argc, char** argv, const std::string& process_name,
                const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitConfig;
  }
  initLogging(process_name);
  try {
    return body();
  } catch (const ConfigError& e) {
    spdlog::error("{}", e.what());
    return kExitConfig;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitFailed;
  }
}

}  // namespace climbsim
