#pragma once
/// @file
/// The depth grids of a recording (RUN_DIR/run.mcap, scene/DepthGrid; docs/recordings.md) as
/// `view RUN_DIR` serves them: what viewer/depth_grids.jsonl holds, for a run directory that
/// has the recording only.

#include <string>
#include <utility>
#include <vector>

namespace climbsim::viewer {

/// (t [s], heightGridJson text) of every scene/DepthGrid message of the recording `path`, in
/// file order; empty if it has none. ConfigError (one line naming the file) if it is cut short,
/// corrupt or no recording.
std::vector<std::pair<double, std::string>> recordedDepthGrids(const std::string& path);

}  // namespace climbsim::viewer
