#include "climbsim/dds_discovery.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <sstream>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include "climbsim/errors.hpp"

namespace climbsim {

namespace {
bool isIpv4(const std::string& text) {
  in_addr parsed{};
  return ::inet_pton(AF_INET, text.c_str(), &parsed) == 1;
}

std::string variable(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? std::string(value) : std::string();
}

[[noreturn]] void badVariable(const char* name, const std::string& value, const std::string& why) {
  throw ConfigError(std::string("environment ") + name + " = '" + value + "': " + why);
}

eprosima::fastrtps::rtps::Locator_t udpLocator(const std::string& address) {
  eprosima::fastrtps::rtps::Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  locator.port = 0;  // the well-known ports (initial peers: of every id in the peer range)
  eprosima::fastrtps::rtps::IPLocator::setIPv4(locator, address);
  return locator;
}
}  // namespace

std::optional<UnicastDiscovery> unicastDiscoveryFromEnvironment() {
  const std::string peers = variable(kEnvDdsPeers);
  if (peers.empty()) {
    return std::nullopt;
  }
  UnicastDiscovery discovery;
  std::istringstream items(peers);
  for (std::string item; std::getline(items, item, ',');) {
    if (!isIpv4(item)) {
      badVariable(kEnvDdsPeers, peers, "'" + item + "' is not an IPv4 address");
    }
    discovery.peers.push_back(item);
  }
  discovery.interface_address = variable(kEnvDdsInterface);
  if (!isIpv4(discovery.interface_address)) {
    badVariable(kEnvDdsInterface, discovery.interface_address, "not an IPv4 address (set with " +
                                                                   std::string(kEnvDdsPeers) + ")");
  }
  if (std::find(discovery.peers.begin(), discovery.peers.end(), discovery.interface_address) ==
      discovery.peers.end()) {
    badVariable(kEnvDdsInterface, discovery.interface_address, "not one of " + std::string(kEnvDdsPeers));
  }
  const std::string range = variable(kEnvDdsPeerRange);
  if (!range.empty()) {
    char* end = nullptr;
    const long value = std::strtol(range.c_str(), &end, 10);
    if (end == range.c_str() || *end != '\0' || value < 1 || value > 120) {
      badVariable(kEnvDdsPeerRange, range, "not an integer in 1..120");
    }
    discovery.peer_range = static_cast<std::uint32_t>(value);
  }
  return discovery;
}

void applyUnicastDiscovery(const UnicastDiscovery& discovery, eprosima::fastdds::dds::DomainParticipantQos& qos) {
  using eprosima::fastdds::rtps::UDPv4TransportDescriptor;
  bool has_udp = false;
  for (auto& transport : qos.transport().user_transports) {
    if (auto udp = std::dynamic_pointer_cast<UDPv4TransportDescriptor>(transport)) {
      // A copy: the descriptor from the XML profile is shared by every participant made from it.
      auto limited = std::make_shared<UDPv4TransportDescriptor>(*udp);
      limited->interfaceWhiteList = {discovery.interface_address};
      limited->maxInitialPeersRange = discovery.peer_range;
      transport = limited;
      has_udp = true;
    }
  }
  if (!has_udp) {
    throw ConfigError("unicast discovery across hosts needs the UDPv4 transport in the participant profile");
  }
  auto& builtin = qos.wire_protocol().builtin;
  builtin.initialPeersList.clear();
  for (const auto& peer : discovery.peers) {
    builtin.initialPeersList.push_back(udpLocator(peer));
  }
  // A unicast metatraffic locator and no multicast one: Fast DDS then listens for discovery on
  // this address only, and announces to the initial peers instead of the multicast group.
  builtin.metatrafficUnicastLocatorList.clear();
  builtin.metatrafficMulticastLocatorList.clear();
  builtin.metatrafficUnicastLocatorList.push_back(udpLocator(discovery.interface_address));
}

}  // namespace climbsim
