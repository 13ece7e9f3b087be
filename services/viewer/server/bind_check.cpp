#include "bind_check.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace climbsim::viewer {

namespace {
constexpr int kBadAddress = -1;

/// 0 if a TCP socket binds to address:port, kBadAddress for an address that is not IPv4, else errno.
int bindError(const std::string& address, int port) {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, address.c_str(), &addr.sin_addr) != 1) return kBadAddress;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return errno;
  const int yes = 1;
  // As the server will: a port in TIME_WAIT from a previous viewer is free.
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  const int rc = ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
  const int error = errno;
  ::close(fd);
  return rc == 0 ? 0 : error;
}
}  // namespace

bool portInUse(const std::string& address, int port) {
  return port >= 1 && port <= 65535 && bindError(address, port) == EADDRINUSE;
}

std::string checkBindable(const std::string& address, int port) {
  if (port < 1 || port > 65535) return "--port " + std::to_string(port) + ": not in 1..65535";
  const int error = bindError(address, port);
  if (error == kBadAddress) {
    return "--bind " + address + ": not an IPv4 address (e.g. 127.0.0.1, or 0.0.0.0 for every interface)";
  }
  if (error == 0) return {};
  switch (error) {
    case EADDRINUSE: return "--port " + std::to_string(port) + ": already in use on " + address;
    case EADDRNOTAVAIL: return "--bind " + address + ": not an address of this machine";
    case EACCES: return "--port " + std::to_string(port) + ": needs privileges (use a port >= 1024)";
    default: return "--bind " + address + " --port " + std::to_string(port) + ": " + std::strerror(error);
  }
}

}  // namespace climbsim::viewer
