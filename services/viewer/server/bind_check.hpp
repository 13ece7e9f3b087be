#pragma once
/// @file
/// Before the web server starts: can this process listen on address:port? One line naming
/// what is wrong, so that `climbsim-viewer` can exit 2 with it.

#include <string>

namespace climbsim::viewer {

/// Empty if a TCP socket can be bound to `address` (IPv4 dotted quad, or "0.0.0.0" for every
/// interface) and `port` (1..65535); else the problem, e.g.
/// "--bind 10.1.2.3: not an address of this machine" or "--port 8765: already in use".
std::string checkBindable(const std::string& address, int port);

/// Whether `port` on `address` is taken (binding fails with EADDRINUSE): another process
/// listens there, e.g. the viewer of another run.
bool portInUse(const std::string& address, int port);

}  // namespace climbsim::viewer
