#pragma once
/// @file
/// climbsim-viewer --replay: a finished run directory served to the page, which fetches the
/// trace, the pictures and the depth grids and replays them itself (no DDS).

#include <atomic>

#include "viewer/configure.hpp"

namespace climbsim::viewer {

/// Serves options.replay_dir (trace.csv, scenario.yaml, pictures, viewer/depth_grids.jsonl)
/// until `quit`. ConfigError for a directory that is not a run directory. Returns kExitOk.
int serveReplay(const ViewerOptions& options, const std::atomic<bool>& quit);

}  // namespace climbsim::viewer
