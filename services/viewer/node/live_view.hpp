#pragma once
/// @file
/// climbsim-viewer's live view: an observer of the run on the DDS domain (never on the roster,
/// never gating a step) that pushes the run's state, depth grids and sealing pictures to the
/// pages.

#include <atomic>

#include "climbsim/dds_settings.hpp"
#include "viewer/configure.hpp"

namespace climbsim::viewer {

/// Observes the run on `dds` and serves it until `quit`, or options.linger_s after the run
/// ended. Returns kExitOk.
int serveLive(const ViewerOptions& options, const DdsSettings& dds, const std::atomic<bool>& quit);

}  // namespace climbsim::viewer
