#pragma once
/// @file
/// The run id the launcher gives every process of a run: the clock publishes it
/// in RunStart and Stop, and a participant takes no RunStart or Stop with another.

namespace climbsim {

/// Environment variable holding the run's id (decimal, unsigned 64-bit); the clock gets
/// the same as --run-id. Unset: the first RunStart that names this participant's DDS
/// participant binds the clock.
inline constexpr const char* kEnvRunId = "CLIMBSIM_RUN_ID";

}  // namespace climbsim

namespace climbsim {

/// Environment variable holding the absolute path of the run's compose file, which the
/// launcher gives every process of a run: the recorder names it in run.mcap's metadata.
inline constexpr const char* kEnvComposeFile = "CLIMBSIM_COMPOSE_FILE";

}  // namespace climbsim
