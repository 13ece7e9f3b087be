#include "climbsim/main_guard.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>

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
    // All problems of a file at once: one log line each.
    const std::string text = e.what();
    for (std::size_t start = 0; start <= text.size();) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      spdlog::error("{}", text.substr(start, end - start));
      start = end + 1;
    }
    return kExitConfig;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitFailed;
  }
}

}  // namespace climbsim
