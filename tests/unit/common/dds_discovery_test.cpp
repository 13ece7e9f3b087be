// Unicast discovery across hosts (climbsim/dds_discovery.hpp): what the environment asks for
// and what it does to a participant's QoS.

#include "climbsim/dds_discovery.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include "climbsim/errors.hpp"

namespace climbsim {
namespace {

/// Sets the discovery variables for one test and clears them after it.
class DiscoveryEnvironment : public ::testing::Test {
 protected:
  void TearDown() override {
    for (const char* name : {kEnvDdsPeers, kEnvDdsInterface, kEnvDdsPeerRange}) ::unsetenv(name);
  }
  static void set(const char* name, const char* value) { ::setenv(name, value, 1); }
  static std::string errorOf() {
    try {
      unicastDiscoveryFromEnvironment();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(DiscoveryEnvironment, NothingSetMeansOneHost) { EXPECT_FALSE(unicastDiscoveryFromEnvironment().has_value()); }

TEST_F(DiscoveryEnvironment, ReadsPeersInterfaceAndRange) {
  set(kEnvDdsPeers, "10.77.0.1,10.77.0.2");
  set(kEnvDdsInterface, "10.77.0.2");
  set(kEnvDdsPeerRange, "12");
  const auto discovery = unicastDiscoveryFromEnvironment();
  ASSERT_TRUE(discovery.has_value());
  EXPECT_EQ(discovery->peers, (std::vector<std::string>{"10.77.0.1", "10.77.0.2"}));
  EXPECT_EQ(discovery->interface_address, "10.77.0.2");
  EXPECT_EQ(discovery->peer_range, 12u);
}

TEST_F(DiscoveryEnvironment, BadValuesNameTheVariableAndTheValue) {
  set(kEnvDdsPeers, "10.77.0.1,10.77.0.256");
  set(kEnvDdsInterface, "10.77.0.1");
  EXPECT_NE(errorOf().find("CLIMBSIM_DDS_PEERS = '10.77.0.1,10.77.0.256': '10.77.0.256' is not an IPv4"),
            std::string::npos)
      << errorOf();
  set(kEnvDdsPeers, "10.77.0.1");
  set(kEnvDdsInterface, "10.77.0.9");
  EXPECT_NE(errorOf().find("CLIMBSIM_DDS_INTERFACE = '10.77.0.9': not one of"), std::string::npos) << errorOf();
  set(kEnvDdsInterface, "10.77.0.1");
  set(kEnvDdsPeerRange, "0");
  EXPECT_NE(errorOf().find("CLIMBSIM_DDS_PEER_RANGE = '0'"), std::string::npos) << errorOf();
}

TEST(ApplyUnicastDiscovery, UnicastPeersOwnInterfaceNoMulticastSharedMemoryKept) {
  using namespace eprosima::fastdds::rtps;
  eprosima::fastdds::dds::DomainParticipantQos qos;
  auto shm = std::make_shared<SharedMemTransportDescriptor>();
  auto udp = std::make_shared<UDPv4TransportDescriptor>();
  qos.transport().user_transports = {shm, udp};
  UnicastDiscovery discovery;
  discovery.peers = {"10.77.0.1", "10.77.0.2"};
  discovery.interface_address = "10.77.0.1";
  discovery.peer_range = 10;
  applyUnicastDiscovery(discovery, qos);

  const auto& builtin = qos.wire_protocol().builtin;
  ASSERT_EQ(builtin.initialPeersList.size(), 2u);
  EXPECT_EQ(eprosima::fastrtps::rtps::IPLocator::ip_to_string(*builtin.initialPeersList.begin()), "10.77.0.1");
  EXPECT_EQ(builtin.initialPeersList.begin()->port, 0u);  // the well-known ports of ids 0..range-1
  EXPECT_TRUE(builtin.metatrafficMulticastLocatorList.empty());
  ASSERT_EQ(builtin.metatrafficUnicastLocatorList.size(), 1u);
  EXPECT_EQ(eprosima::fastrtps::rtps::IPLocator::ip_to_string(*builtin.metatrafficUnicastLocatorList.begin()),
            "10.77.0.1");

  ASSERT_EQ(qos.transport().user_transports.size(), 2u);
  EXPECT_EQ(qos.transport().user_transports[0], shm);  // shared memory between processes of one host stays
  auto limited = std::dynamic_pointer_cast<UDPv4TransportDescriptor>(qos.transport().user_transports[1]);
  ASSERT_TRUE(limited);
  EXPECT_NE(limited, udp) << "the profile's descriptor, shared by every participant, must not be changed";
  EXPECT_EQ(limited->interfaceWhiteList, (std::vector<std::string>{"10.77.0.1"}));
  EXPECT_EQ(limited->maxInitialPeersRange, 10u);
  EXPECT_TRUE(udp->interfaceWhiteList.empty());
}

TEST(ApplyUnicastDiscovery, NeedsAUdpTransport) {
  eprosima::fastdds::dds::DomainParticipantQos qos;
  qos.transport().user_transports = {std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>()};
  UnicastDiscovery discovery;
  discovery.peers = {"10.77.0.1"};
  discovery.interface_address = "10.77.0.1";
  EXPECT_THROW(applyUnicastDiscovery(discovery, qos), ConfigError);
}

}  // namespace
}  // namespace climbsim
