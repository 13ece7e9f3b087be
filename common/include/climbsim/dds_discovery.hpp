#pragma once
/// @file
/// DDS discovery for compositions across several hosts. On one host Fast DDS finds its
/// peers by multicast; across hosts the launcher tells every process (by environment) the
/// addresses of all hosts of the run and the address of its own, and each participant then
/// announces itself by unicast to those peers (SPDP initial peers), listens for discovery on
/// its own address only, and sends UDP only through that interface: no multicast, no traffic
/// on any other network.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "climbsim/dds_discovery_env.hpp"

namespace climbsim {

/// Unicast discovery of one participant.
struct UnicastDiscovery {
  std::vector<std::string> peers;  ///< IPv4 address of every host of the run (this one included)
  std::string interface_address;   ///< IPv4 address of this host: the only UDP interface used
  /// Participant ids 0..peer_range-1 are probed at every peer: the well-known metatraffic port
  /// 7400 + 250 domain + 10 + 2 id of each. Must exceed the number of participants per host.
  std::uint32_t peer_range = 16;
};

/// The unicast discovery the environment asks for, or nothing when CLIMBSIM_DDS_PEERS is not
/// set (one host: multicast discovery, as Fast DDS does by default). Throws ConfigError naming
/// the variable and its value if an address is not IPv4, the interface is missing or not one
/// of the peers, or the range is not an integer in 1..120.
std::optional<UnicastDiscovery> unicastDiscoveryFromEnvironment();

/// Changes `qos` for `discovery`: initial peers (port 0: the well-known ports of ids
/// 0..peer_range-1), metatraffic unicast on the interface address, the UDPv4 transport limited
/// to that interface (the shared-memory transport stays: Fast DDS uses it only between
/// processes of one host). Throws ConfigError if `qos` has no UDPv4 user transport.
void applyUnicastDiscovery(const UnicastDiscovery& discovery, eprosima::fastdds::dds::DomainParticipantQos& qos);

}  // namespace climbsim
