#include "security_material.hpp"

#include <fnmatch.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <spdlog/spdlog.h>

#include "climbsim/dds_security_env.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/process.hpp"
#include "climbsim/program_topics.hpp"
#include "climbsim/security_files.hpp"
#include "launch_plan.hpp"

namespace climbsim::launcher {

namespace fs = std::filesystem;

namespace {
/// Validity of the CA, the certificates and the permissions [days]: longer than any run.
constexpr int kValidDays = 30;

void appendUnique(std::vector<std::string>& to, const std::vector<std::string>& from) {
  for (const auto& topic : from) {
    if (std::find(to.begin(), to.end(), topic) == to.end()) to.push_back(topic);
  }
}

/// `when` as the permissions document writes times (UTC, "2026-12-02T00:00:00").
std::string isoTime(std::chrono::system_clock::time_point when) {
  const std::time_t t = std::chrono::system_clock::to_time_t(when);
  std::tm utc{};
  ::gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  return text;
}

std::string topicList(const std::vector<std::string>& topics) {
  std::string xml;
  for (const auto& topic : topics) xml += "            <topic>" + topic + "</topic>\n";
  return xml;
}

void writePrivate(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
}

/// Runs `openssl args...`; throws with its output if it fails.
void openssl(const std::string& program, const std::vector<std::string>& args, const fs::path& log) {
  ProcessSpec spec;
  spec.argv = {program};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  fs::remove(log);
  spec.output_file = log.string();
  ChildProcess child(spec);
  const auto code = child.waitFor(std::chrono::seconds(60));
  if (!code || *code != 0) {
    std::ifstream in(log);
    std::stringstream output;
    output << in.rdbuf();
    std::string command = program;
    for (const auto& a : args) command += " " + a;
    throw std::runtime_error("security: `" + command + "` failed (exit " + (code ? std::to_string(*code) : "none") +
                             "): " + output.str());
  }
}

std::string findOpenssl(const std::string& path_env) {
  std::size_t begin = 0;
  while (begin <= path_env.size()) {
    const std::size_t colon = path_env.find(':', begin);
    const std::string dir = path_env.substr(begin, colon == std::string::npos ? std::string::npos : colon - begin);
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "openssl";
    if (!dir.empty() && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    if (colon == std::string::npos) break;
    begin = colon + 1;
  }
  throw ConfigError("security: on needs the program 'openssl' (Debian package openssl) on PATH to make the run's "
                    "certificates; install it (./deploy/climbsim setup)");
}
}  // namespace

std::vector<SecurityGrant> securityGrants(const ComposeFile& compose) {
  std::vector<SecurityGrant> grants;
  const ProgramTopics lockstep = lockstepTopics();
  const auto* clock = findProgramTopics("climbsim-clock");
  grants.push_back({kClockProcessName, compose.clock.host, clock->writes, clock->reads});
  for (const auto& service : compose.services) {
    const std::string program = fs::path(service.command.front()).filename().string();
    const ProgramTopics* topics = findProgramTopics(program);
    if (topics == nullptr) {
      const bool python = program.rfind("climbsim-py-", 0) == 0 || fs::path(program).extension() == ".py";
      const bool c_client = program.rfind("climbsim-c-", 0) == 0;
      throw ConfigError(compose.source + ":" + std::to_string(service.line) + ": services." + service.name +
                        ".command[0] = " + program + ": " +
                        (python ? "a Python client cannot join a secured run (the cyclonedds wheel from PyPI has no "
                                  "DDS Security); run it without security: on / --secure"
                         : c_client ? "the C client cannot join a secured run (Cyclone DDS 0.10's handshake with Fast "
                                      "DDS 2.9 fails for some participants; see docs/deployment.md#dds-security); "
                                      "run it without security: on / --secure"
                                    : "security: on grants only climbsim's own programs (climbsim/program_topics.hpp); "
                                      "no permissions can be made for it"));
    }
    for (const auto& instance : service.instanceNames()) {
      SecurityGrant grant{instance, service.host, topics->writes, topics->reads};
      if (topics->lockstep && !service.observer) {
        appendUnique(grant.writes, lockstep.writes);
        appendUnique(grant.reads, lockstep.reads);
      }
      grants.push_back(std::move(grant));
    }
  }
  const auto* clockctl = findProgramTopics(kClockCtlName);
  grants.push_back({kClockCtlName, kLocalHost, clockctl->writes, clockctl->reads});
  return grants;
}

const std::vector<TopicProtection>& topicProtections() {
  static const std::vector<TopicProtection> rules = {
      {"clock/*", "ENCRYPT",
       "the run's control plane (grants, progress, start with the roster's identities, stop, pause): secret and "
       "authentic; few and small samples"},
      {"record/*", "ENCRYPT",
       "record and observer batches: they name the topics of the samples they carry, and topic names are secret; "
       "one batch per producer every few steps"},
      {"*", "NONE",
       "step data: authentic (every RTPS message is signed), readable on the network: the simulated robot's "
       "state is no secret; most of the bytes and messages of a run"},
  };
  return rules;
}

const TopicProtection& protectionOf(const std::string& topic) {
  for (const auto& rule : topicProtections()) {
    if (::fnmatch(rule.expression.c_str(), topic.c_str(), 0) == 0) return rule;
  }
  return topicProtections().back();
}

std::string governanceXml(int domain_id) {
  const std::string domain = std::to_string(domain_id);
  std::string rules;
  for (const auto& rule : topicProtections()) {
    // The endpoints of every topic are discovered encrypted (topic and type names stay
    // secret), every reader and writer needs its permission, and the submessages are covered
    // by the signature of the RTPS message that carries them (metadata NONE: not twice).
    rules += "        <!-- " + rule.why + " -->\n";
    rules += R"(        <topic_rule>
          <topic_expression>)" + rule.expression + R"(</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>NONE</metadata_protection_kind>
          <data_protection_kind>)" + rule.data + R"(</data_protection_kind>
        </topic_rule>
)";
  }
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- climbsim: governance of a secured run (made by the launcher, signed by the run's CA) -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id>)" + domain + R"(</id></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>SIGN</liveliness_protection_kind>
      <rtps_protection_kind>SIGN</rtps_protection_kind>
      <topic_access_rules>
)" + rules + R"(      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
)";
}

/// Every stamped writer is also in the DDS partition "climbsim.from.<name>" besides the default
/// one, and a reader that names its producers subscribes in theirs (DdsContext); Fast DDS's
/// access control then checks each partition against the rule, so the rules allow any.
constexpr const char* kAnyPartition = "          <partitions><partition>*</partition></partitions>\n";

std::string permissionsXml(const SecurityGrant& grant, int domain_id, int days) {
  const auto now = std::chrono::system_clock::now();
  std::string xml = R"(<?xml version="1.0" encoding="UTF-8"?>
<!-- climbsim: what ')" + grant.identity + R"(' may publish and subscribe to in this run -->
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name=")" + grant.identity + R"(">
      <subject_name>CN=)" + grant.identity + R"(</subject_name>
      <validity>
        <not_before>)" + isoTime(now - std::chrono::hours(1)) + R"(</not_before>
        <not_after>)" + isoTime(now + std::chrono::hours(24 * days)) + R"(</not_after>
      </validity>
      <allow_rule>
        <domains><id>)" + std::to_string(domain_id) + R"(</id></domains>
)";
  if (!grant.writes.empty()) {
    xml += "        <publish>\n          <topics>\n" + topicList(grant.writes) + "          </topics>\n" + kAnyPartition +
           "        </publish>\n";
  }
  if (!grant.reads.empty()) {
    xml += "        <subscribe>\n          <topics>\n" + topicList(grant.reads) + "          </topics>\n" + kAnyPartition +
           "        </subscribe>\n";
  }
  xml += R"(      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
)";
  return xml;
}

void makeSecurityMaterial(const std::string& dir_text, int domain_id, const std::vector<SecurityGrant>& grants,
                          const std::string& path_env) {
  const std::string program = findOpenssl(path_env);
  const fs::path dir(dir_text);
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_all, fs::perm_options::replace);
  const fs::path log = dir / "openssl.log";
  const std::string ca_cert = (dir / security_files::kCaCert).string();
  const std::string ca_key = (dir / security_files::kCaKey).string();
  const std::string days = std::to_string(kValidDays);
  openssl(program, {"req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout", ca_key,
                    "-out", ca_cert, "-subj", "/CN=climbsim run CA", "-days", days, "-sha256"},
          log);
  fs::permissions(ca_key, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
  auto sign = [&](const fs::path& xml, const fs::path& signed_file) {
    openssl(program, {"smime", "-sign", "-in", xml.string(), "-text", "-out", signed_file.string(), "-signer", ca_cert,
                      "-inkey", ca_key},
            log);
  };
  writePrivate(dir / "governance.xml", governanceXml(domain_id));
  sign(dir / "governance.xml", dir / security_files::kGovernance);
  for (const auto& grant : grants) {
    const fs::path own = dir / grant.identity;
    fs::create_directories(own);
    fs::permissions(own, fs::perms::owner_all, fs::perm_options::replace);
    const std::string key = (own / security_files::kKey).string();
    const std::string request = (own / "identity.csr").string();
    openssl(program, {"req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:P-256", "-nodes", "-keyout", key,
                      "-out", request, "-subj", "/CN=" + grant.identity},
            log);
    fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
    openssl(program, {"x509", "-req", "-in", request, "-CA", ca_cert, "-CAkey", ca_key, "-CAcreateserial", "-CAserial",
                      (dir / "ca.srl").string(), "-days", days, "-sha256", "-out", (own / security_files::kCert).string()},
            log);
    fs::remove(request);
    writePrivate(own / "permissions.xml", permissionsXml(grant, domain_id, kValidDays));
    sign(own / "permissions.xml", own / security_files::kPermissions);
  }
  // Everything is signed: without the CA's key nobody mints another identity for this run.
  fs::remove(ca_key);
  fs::remove(dir / "ca.srl");
  fs::remove(log);
  for (const auto& grant : grants) {
    checkSecurityFiles(securityFilesIn(dir.string(), grant.identity));
  }
}

void copySecurityMaterial(const ComposeFile& compose, const std::string& dir, const std::vector<SecurityGrant>& grants) {
  for (const HostSpec* host : compose.usedHosts()) {
    if (host->kind != HostKind::ssh) continue;
    std::string files = shellQuoted(security_files::kCaCert) + " " + shellQuoted(security_files::kGovernance);
    int identities = 0;
    for (const auto& grant : grants) {
      if (grant.host == host->name) {
        files += " " + shellQuoted(grant.identity);
        ++identities;
      }
    }
    // Unpacked beside, then copied in: the host may share this machine's files (the same
    // directory), which an unpacking in place would truncate while it is read.
    const std::string remote = "umask 077 && t=$(mktemp -d) && tar -C \"$t\" -xf - && mkdir -p " + shellQuoted(dir) +
                               " && cp -a \"$t\"/. " + shellQuoted(dir) + "/ && rm -rf \"$t\"";
    std::string ssh = "ssh -o BatchMode=yes -o LogLevel=ERROR";
    for (const auto& option : host->ssh_options) ssh += " " + shellQuoted(option);
    ssh += " " + shellQuoted(host->target) + " -- " + shellQuoted(remote);
    ProcessSpec spec;
    spec.argv = {"sh", "-c", "tar -C " + shellQuoted(dir) + " -cf - " + files + " | " + ssh};
    const fs::path log = fs::path(dir) / ("copy-" + host->name + ".log");
    spec.output_file = log.string();
    ChildProcess copy(spec);
    const auto code = copy.waitFor(std::chrono::seconds(60));
    if (!code || *code != 0) {
      std::ifstream in(log);
      std::stringstream output;
      output << in.rdbuf();
      throw std::runtime_error("security: cannot copy the run's certificates to host '" + host->name + "' (" +
                               host->target + "): " + output.str());
    }
    fs::remove(log);
    spdlog::info("security: copied the CA certificate, the governance and {} identities to host '{}' ({})", identities,
                 host->name, host->target);
  }
}

std::map<std::string, std::string> securityEnvironment(const std::string& dir, const std::string& identity) {
  return {{kEnvSecurityDir, dir}, {kEnvSecurityIdentity, identity}};
}

}  // namespace climbsim::launcher
