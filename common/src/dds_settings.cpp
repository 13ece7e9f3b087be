#include "climbsim/dds_settings.hpp"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <fstream>

#include "climbsim/errors.hpp"

#ifndef CLIMBSIM_DEFAULT_QOS_FILE
#error "CLIMBSIM_DEFAULT_QOS_FILE must be defined by the build"
#endif

namespace climbsim {

namespace {
std::optional<std::string> env(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') {
    return std::nullopt;
  }
  return std::string(value);
}
}  // namespace

int parseDomainId(const std::string& source, const std::string& text) {
  std::size_t used = 0;
  long value = -1;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty()) {
    throw ConfigError(source + " = '" + text + "' is not an integer domain id");
  }
  if (value < 0 || value > kMaxDomainId) {
    throw ConfigError(source + " = " + text + " is out of range; a domain id is 0.." +
                      std::to_string(kMaxDomainId));
  }
  return static_cast<int>(value);
}

void DdsSettings::addOptions(CLI::App& app) {
  app.add_option("--domain", domain_text, "DDS domain id, 0..232 (default: $CLIMBSIM_DOMAIN)");
  app.add_option("--qos", qos_file, "QoS profile XML file (default: $CLIMBSIM_QOS_FILE or deploy/qos/climbsim.xml)");
}

void DdsSettings::resolve() {
  if (!domain_text.empty()) {
    domain_id = parseDomainId("--domain", domain_text);
  }
  if (domain_id < 0) {
    const auto from_env = env("CLIMBSIM_DOMAIN");
    if (!from_env) {
      throw ConfigError("no DDS domain id: give --domain or set CLIMBSIM_DOMAIN (0.." +
                        std::to_string(kMaxDomainId) + ")");
    }
    domain_id = parseDomainId("CLIMBSIM_DOMAIN", *from_env);
  }
  std::string source = "--qos";
  if (qos_file.empty()) {
    if (const auto from_env = env("CLIMBSIM_QOS_FILE")) {
      qos_file = *from_env;
      source = "CLIMBSIM_QOS_FILE";
    } else {
      qos_file = CLIMBSIM_DEFAULT_QOS_FILE;
      source = "default QoS file";
    }
  }
  std::ifstream probe(qos_file);
  if (!probe.good()) {
    throw ConfigError(source + " = '" + qos_file + "': cannot read the QoS profile file");
  }
}

std::size_t shmSegmentBytes(std::size_t base_bytes, std::size_t largest_sample_bytes) {
  return base_bytes + kImagesInFlight * largest_sample_bytes;
}

}  // namespace climbsim
