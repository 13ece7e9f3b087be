#pragma once
/// @file
/// The environment variables by which the launcher sets up DDS discovery across hosts
/// (read by climbsim/dds_discovery.hpp; no DDS header here, so the launcher needs none).

namespace climbsim {

/// Environment variables the launcher sets for every process of a multi-host run.
inline constexpr const char* kEnvDdsPeers = "CLIMBSIM_DDS_PEERS";           ///< "10.77.0.1,10.77.0.2"
inline constexpr const char* kEnvDdsInterface = "CLIMBSIM_DDS_INTERFACE";   ///< this host's address
inline constexpr const char* kEnvDdsPeerRange = "CLIMBSIM_DDS_PEER_RANGE";  ///< participant ids per peer

}  // namespace climbsim
