// Port in use and a bind address that is not this machine's: one line naming them.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "bind_check.hpp"

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

TEST(ViewerBindCheck, AddressNotOfThisMachineIsNamed) {
  EXPECT_EQ(checkBindable("192.0.2.77", 8765), "--bind 192.0.2.77: not an address of this machine");
  EXPECT_NE(checkBindable("localhost-ish", 8765).find("--bind localhost-ish: not an IPv4 address"), std::string::npos);
  EXPECT_NE(checkBindable("127.0.0.1", 0).find("--port 0"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::viewer
