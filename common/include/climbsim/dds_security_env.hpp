#pragma once
/// @file
/// How the launcher hands a process the DDS Security files of a secured run:
/// the directory it made and the identity to load from it. No DDS or OpenSSL header here,
/// so that the launcher needs neither to name them.
///
/// Layout of a security directory (all made by the launcher; keys 0600):
///   ca.cert.pem                       the run's CA: identity CA and permissions CA
///   governance.p7s                    the governance document, S/MIME-signed by the CA
///   <identity>/identity.cert.pem      the participant's certificate (subject CN=<identity>)
///   <identity>/identity.key.pem       its private key
///   <identity>/permissions.p7s        its permissions document, S/MIME-signed by the CA

namespace climbsim {

/// The run's security directory; unset or empty: DDS Security off.
inline constexpr const char* kEnvSecurityDir = "CLIMBSIM_DDS_SECURITY_DIR";
/// The identity (sub-directory) to load; unset: the process's DDS participant name.
inline constexpr const char* kEnvSecurityIdentity = "CLIMBSIM_DDS_SECURITY_IDENTITY";

/// File names inside a security directory.
namespace security_files {
inline constexpr const char* kCaCert = "ca.cert.pem";
inline constexpr const char* kCaKey = "ca.key.pem";  ///< stays with the launcher: never copied to a host
inline constexpr const char* kGovernance = "governance.p7s";
inline constexpr const char* kCert = "identity.cert.pem";
inline constexpr const char* kKey = "identity.key.pem";
inline constexpr const char* kPermissions = "permissions.p7s";
}  // namespace security_files

}  // namespace climbsim
