#pragma once
/// @file
/// DDS Security of a secured run: a participant loads its identity certificate,
/// private key, the run's CA, governance and its permissions through Fast DDS 2.9's builtin
/// plugins (PKI-DH authentication, Access-Permissions, AES-GCM-GMAC), set as participant
/// properties. The files come from the launcher (climbsim/security_files.hpp).

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "climbsim/security_files.hpp"

namespace climbsim {

/// Sets the properties that make Fast DDS load the builtin security plugins with `files`.
void applySecurity(const SecurityFiles& files, eprosima::fastdds::dds::DomainParticipantQos& qos);

}  // namespace climbsim
