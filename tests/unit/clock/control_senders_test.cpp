// Who may send ClockControl (compose clock.control).

#include "control_senders.hpp"

#include <gtest/gtest.h>

#include "climbsim/errors.hpp"

namespace climbsim::clock {
namespace {

TEST(ControlSenders, NamesAndHostsAreParsedAndFormattedBack) {
  const auto senders = parseControlSenders("--control-from", "climbsim-clockctl@127.0.0.1/10.77.0.1/shm,viewer");
  ASSERT_EQ(senders.size(), 2u);
  EXPECT_EQ(senders[0].name, "climbsim-clockctl");
  EXPECT_EQ(senders[0].addresses, (std::vector<std::string>{"127.0.0.1", "10.77.0.1", "shm"}));
  EXPECT_TRUE(senders[1].addresses.empty());
  EXPECT_EQ(formatControlSenders(senders), "climbsim-clockctl@127.0.0.1/10.77.0.1/shm,viewer");
  EXPECT_TRUE(parseControlSenders("--control-from", "").empty());
}

TEST(ControlSenders, BadEntriesNameTheOption) {
  try {
    parseControlSenders("--control-from", "ok,bad name");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--control-from entry 'bad name'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseControlSenders("--control-from", "clockctl@"), ConfigError);
  EXPECT_THROW(parseControlSenders("--control-from", "clockctl@1.2.3.4//shm"), ConfigError);
}

TEST(ControlSenders, OnlyListedNamesFromTheirHostsMayControl) {
  const auto allowed = parseControlSenders("x", "climbsim-clockctl@10.77.0.1/shm,viewer");
  EXPECT_EQ(controlRefusal(allowed, "climbsim-clockctl", {"shm"}), "");
  EXPECT_EQ(controlRefusal(allowed, "climbsim-clockctl", {"192.168.1.5", "10.77.0.1"}), "");
  EXPECT_EQ(controlRefusal(allowed, "viewer", {"10.99.0.9"}), "") << "no host listed: any";
  EXPECT_NE(controlRefusal(allowed, "climbsim-clockctl", {"10.77.0.2"}).find("only from its listed host"),
            std::string::npos);
  EXPECT_NE(controlRefusal(allowed, "outsider", {"shm"}).find("'outsider' is not among the senders"),
            std::string::npos);
  EXPECT_NE(controlRefusal({}, "climbsim-clockctl", {"shm"}), "") << "an empty list allows nobody";
}

}  // namespace
}  // namespace climbsim::clock
