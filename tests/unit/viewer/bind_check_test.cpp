// Port in use and a bind address that is not this machine's: one line naming them.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bind_check.hpp"
#include "climbsim/errors.hpp"
#include "web_server.hpp"

namespace climbsim::viewer {
namespace {

TEST(ViewerBindCheck, PortInUseIsNamed) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(fd, 1), 0);
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  const int port = ntohs(addr.sin_port);
  EXPECT_EQ(checkBindable("127.0.0.1", port), "--port " + std::to_string(port) + ": already in use on 127.0.0.1");
  ::close(fd);
  EXPECT_EQ(checkBindable("127.0.0.1", port), "");
}

/// A socket listening on a free loopback port; its port.
int listenOnAFreePort(int& fd) {
  fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 1) != 0) return -1;
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  return ntohs(addr.sin_port);
}

TEST(ViewerBindCheck, ATakenPortIsTakenAndWithTriesTheServerTakesTheNextFreeOne) {
  int fd = -1;
  const int port = listenOnAFreePort(fd);
  ASSERT_GT(port, 0);
  ASSERT_LT(port, 65000);
  EXPECT_TRUE(portInUse("127.0.0.1", port));
  const std::filesystem::path web = std::filesystem::temp_directory_path() / ("climbsim-web-" + std::to_string(::getpid()));
  std::filesystem::create_directories(web);
  std::ofstream(web / "index.html") << "<title>test</title>\n";
  WebServer::Options options;
  options.port = port;
  options.web_dir = web.string();
  // One try (an explicit port): taken is an error naming it.
  try {
    WebServer refused(options);
    ADD_FAILURE() << "a taken port was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "--port " + std::to_string(port) + ": already in use on 127.0.0.1");
  }
  // Tries (the compose file's default port): the next free one, and url() says which.
  options.port_tries = 5;
  {
    const WebServer server(options);
    EXPECT_GT(server.port(), port);
    EXPECT_LT(server.port(), port + 5);
    EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
    EXPECT_TRUE(portInUse("127.0.0.1", server.port()));
  }
  ::close(fd);
  EXPECT_FALSE(portInUse("127.0.0.1", port));
  std::filesystem::remove_all(web);
}

TEST(ViewerBindCheck, AddressNotOfThisMachineIsNamed) {
  EXPECT_EQ(checkBindable("192.0.2.77", 8765), "--bind 192.0.2.77: not an address of this machine");
  EXPECT_NE(checkBindable("localhost-ish", 8765).find("--bind localhost-ish: not an IPv4 address"), std::string::npos);
  EXPECT_NE(checkBindable("127.0.0.1", 0).find("--port 0"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::viewer
