#pragma once
/// @file
/// The common frame of every climbsim executable's main().

#include <functional>
#include <string>

namespace CLI {
class App;
}

namespace climbsim {

/// Parses the command line with `app`, sets up logging as `process_name` and runs `body`.
/// What goes wrong becomes one error line and an exit code: a bad command line or a
/// ConfigError gives kExitConfig, any other exception kExitFailed; otherwise body's code.
int guardedMain(CLI::App& app, int argc, char** argv, const std::string& process_name,
                const std::function<int()>& body);

}  // namespace climbsim
