#include "climbsim/dds_security.hpp"

namespace climbsim {

void applySecurity(const SecurityFiles& files, eprosima::fastdds::dds::DomainParticipantQos& qos) {
  auto& properties = qos.properties().properties();
  auto set = [&](const std::string& name, const std::string& value) { properties.emplace_back(name, value); };
  const std::string file = "file://";
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", file + files.ca_cert);
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", file + files.cert);
  set("dds.sec.auth.builtin.PKI-DH.private_key", file + files.key);
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", file + files.ca_cert);
  set("dds.sec.access.builtin.Access-Permissions.governance", file + files.governance);
  set("dds.sec.access.builtin.Access-Permissions.permissions", file + files.permissions);
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace climbsim
