#pragma once
/// @file
/// The DDS Security files of one participant of a secured run and their checks
/// (OpenSSL, no DDS): the services check them before they create their participant, the
/// launcher once it has made them. Layout: climbsim/dds_security_env.hpp.

#include <optional>
#include <string>

namespace climbsim {

/// The files one participant loads, all absolute paths.
struct SecurityFiles {
  std::string identity;     ///< the identity's name (certificate subject CN, for messages)
  std::string ca_cert;      ///< identity CA and permissions CA (PEM)
  std::string governance;   ///< S/MIME-signed governance document
  std::string cert;         ///< the identity certificate (PEM)
  std::string key;          ///< its private key (PEM)
  std::string permissions;  ///< S/MIME-signed permissions document
};

/// The files of `identity` in the security directory `dir`.
SecurityFiles securityFilesIn(const std::string& dir, const std::string& identity);

/// The files named by CLIMBSIM_DDS_SECURITY_DIR and CLIMBSIM_DDS_SECURITY_IDENTITY (default
/// identity: `participant_name`); nothing when security is off (no directory set).
std::optional<SecurityFiles> securityFilesFromEnvironment(const std::string& participant_name);

/// Checks, before any DDS entity exists, that every file is there and readable and that the
/// identity certificate is within its validity period. Throws ConfigError, one line naming the
/// participant and the file: "participant 'thermo': DDS Security key '/r/security/thermo/
/// identity.key.pem': cannot read it (No such file or directory)".
void checkSecurityFiles(const SecurityFiles& files);


}  // namespace climbsim
