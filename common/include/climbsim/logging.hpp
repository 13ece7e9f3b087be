#pragma once
/// @file
/// Logging set-up shared by every executable (spdlog, to stderr).

#include <string>

namespace climbsim {

/// Names the process in every line; level from CLIMBSIM_LOG_LEVEL (trace, debug, info,
/// warn, error; default info).
void initLogging(const std::string& process_name);

}  // namespace climbsim
