#include "climbsim/security_files.hpp"

#include <openssl/pem.h>
#include <openssl/x509.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "climbsim/dds_security_env.hpp"
#include "climbsim/errors.hpp"

namespace climbsim {

namespace {
std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? value : "";
}

[[noreturn]] void refuse(const SecurityFiles& files, const std::string& what, const std::string& path,
                         const std::string& why) {
  throw ConfigError("participant '" + files.identity + "': DDS Security " + what + " '" + path + "': " + why);
}

/// Opens `path` for reading, or refuses naming it.
std::unique_ptr<FILE, int (*)(FILE*)> openOrRefuse(const SecurityFiles& files, const std::string& what,
                                                    const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "r");
  if (file == nullptr) {
    refuse(files, what, path, std::string("cannot read it (") + std::strerror(errno) + ")");
  }
  return {file, &std::fclose};
}

/// The certificate in `path`; refuses it if it is no PEM certificate or outside its validity.
void checkCertificate(const SecurityFiles& files, const std::string& what, const std::string& path) {
  auto file = openOrRefuse(files, what, path);
  std::unique_ptr<X509, void (*)(X509*)> cert(PEM_read_X509(file.get(), nullptr, nullptr, nullptr), &X509_free);
  if (!cert) {
    refuse(files, what, path, "not a PEM certificate");
  }
  if (X509_cmp_current_time(X509_get0_notAfter(cert.get())) <= 0) {
    refuse(files, what, path, "the certificate has expired");
  }
  if (X509_cmp_current_time(X509_get0_notBefore(cert.get())) >= 0) {
    refuse(files, what, path, "the certificate is not valid yet");
  }
}

void checkKey(const SecurityFiles& files, const std::string& path) {
  auto file = openOrRefuse(files, "private key", path);
  std::unique_ptr<EVP_PKEY, void (*)(EVP_PKEY*)> key(PEM_read_PrivateKey(file.get(), nullptr, nullptr, nullptr),
                                                     &EVP_PKEY_free);
  if (!key) {
    refuse(files, "private key", path, "not a PEM private key (or one with a passphrase)");
  }
}
}  // namespace

SecurityFiles securityFilesIn(const std::string& dir, const std::string& identity) {
  SecurityFiles files;
  files.identity = identity;
  const auto base = std::filesystem::absolute(dir).lexically_normal();
  files.ca_cert = (base / security_files::kCaCert).string();
  files.governance = (base / security_files::kGovernance).string();
  files.cert = (base / files.identity / security_files::kCert).string();
  files.key = (base / files.identity / security_files::kKey).string();
  files.permissions = (base / files.identity / security_files::kPermissions).string();
  return files;
}

std::optional<SecurityFiles> securityFilesFromEnvironment(const std::string& participant_name) {
  const std::string dir = environment(kEnvSecurityDir);
  if (dir.empty()) {
    return std::nullopt;
  }
  const std::string identity = environment(kEnvSecurityIdentity);
  return securityFilesIn(dir, identity.empty() ? participant_name : identity);
}

void checkSecurityFiles(const SecurityFiles& files) {
  checkCertificate(files, "CA certificate", files.ca_cert);
  openOrRefuse(files, "governance", files.governance);
  checkCertificate(files, "certificate", files.cert);
  checkKey(files, files.key);
  openOrRefuse(files, "permissions", files.permissions);
}

}  // namespace climbsim
