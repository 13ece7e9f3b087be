#pragma once
/// @file
/// The viewer's port when runs go side by side: a second `up` finds the default port 8765
/// taken by the first run's viewer. A viewer whose port is the compose file's default takes the
/// next free one (climbsim-viewer --port-tries); a port written into the compose file on
/// purpose stays what it is (taken: the viewer refuses it in one line, exit 2).

#include <optional>
#include <string>
#include <string_view>

#include "compose_file.hpp"

namespace climbsim::launcher {

/// climbsim-viewer's default --port (deploy/compose.yaml's too).
inline constexpr int kDefaultViewerPort = 8765;
/// Ports a viewer on the default port tries: 8765 .. 8784.
inline constexpr int kViewerPortTries = 20;

/// Appends `--port-tries kViewerPortTries` to every climbsim-viewer service whose --port is
/// kDefaultViewerPort or not given, unless its command has --port-tries already. Returns how
/// many services it changed.
int letViewersFindAFreePort(ComposeFile& compose);

/// The address of a viewer's "open http://HOST:PORT/ ..." line, if the line is one.
std::optional<std::string> viewerAddressIn(std::string_view line);

}  // namespace climbsim::launcher
