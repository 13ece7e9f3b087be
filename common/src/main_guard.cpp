#include "climbsim/main_guard.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include <fastdds/dds/log/Log.hpp>

#include <CLI/CLI.hpp>

#include "climbsim/errors.hpp"
#include "climbsim/leave_after_results.hpp"
#include "climbsim/logging.hpp"

namespace climbsim {

namespace {

/// Ends a process whose results are complete and whose participant has left: every log line
/// and stream written out, then exit without static destructors. Their only work left is Fast
/// DDS's participant factory, which sleeps 100 ms in its destructor: on every service of
/// every run, before the launcher sees the run end.
[[noreturn]] void endWithoutStaticTeardown(int code) {
  eprosima::fastdds::dds::Log::Flush();
  spdlog::shutdown();
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(code);
}

}  // namespace

int guardedMain(CLI::App& app, int argc, char** argv, const std::string& process_name,
                const std::function<int()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitConfig;
  }
  initLogging(process_name);
  try {
    const int code = body();
    if (resultsComplete()) endWithoutStaticTeardown(code);
    return code;
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
