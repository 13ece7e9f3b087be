// A second run's viewer on the default port takes the next free one; a port chosen on purpose
// stays as it is. The launcher reads the address the viewer took from its "open ..." line.

#include <gtest/gtest.h>

#include "viewer_port.hpp"

namespace climbsim::launcher {
namespace {

ServiceSpec service(std::vector<std::string> command) {
  ServiceSpec s;
  s.name = "viewer";
  s.observer = true;
  s.command = std::move(command);
  return s;
}

TEST(ViewerPort, OnlyTheDefaultPortLooksFurther) {
  ComposeFile compose;
  compose.services = {service({"climbsim-viewer", "--scenario", "x", "--port", "8765"}),  // deploy/compose.yaml
                      service({"/opt/bin/climbsim-viewer"}),                              // no --port: the default
                      service({"climbsim-viewer", "--port=9000"}),                        // on purpose
                      service({"climbsim-viewer", "--port", "8765", "--port-tries", "3"}),  // said already
                      service({"climbsim-thermo", "--port", "8765"})};                    // not a viewer
  EXPECT_EQ(letViewersFindAFreePort(compose), 2);
  const std::vector<std::string> tries = {"--port-tries", std::to_string(kViewerPortTries)};
  const auto ends_with_tries = [&](const std::vector<std::string>& c) {
    return c.size() >= 2 && std::vector<std::string>(c.end() - 2, c.end()) == tries;
  };
  EXPECT_TRUE(ends_with_tries(compose.services[0].command));
  EXPECT_TRUE(ends_with_tries(compose.services[1].command));
  EXPECT_EQ(compose.services[2].command.size(), 2u) << "an explicit port that is taken stays an error";
  EXPECT_EQ(compose.services[3].command.size(), 5u);
  EXPECT_EQ(compose.services[4].command.size(), 3u);
  EXPECT_EQ(letViewersFindAFreePort(compose), 0) << "once";
}

TEST(ViewerPort, TheAddressComesFromTheViewersOpenLine) {
  EXPECT_EQ(viewerAddressIn("12:00:01.5 viewer info: open http://127.0.0.1:8766/ (DDS domain 7; port 8765 is taken)"),
            std::optional<std::string>("http://127.0.0.1:8766/"));
  EXPECT_EQ(viewerAddressIn("open http://host:8765/"), std::optional<std::string>("http://host:8765/"));
  EXPECT_EQ(viewerAddressIn("drive: wheel 1 stands over nothing"), std::nullopt);
}

}  // namespace
}  // namespace climbsim::launcher
