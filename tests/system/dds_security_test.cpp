// DDS Security of a secured run: `run --secure` gives the unsecured trace
// bit for bit, here and across two hosts; an outsider without the run's certificates, or with
// certificates of another CA, sees no participant and no sample; on the veth link between the
// hosts every RTPS message but the announcements and the handshake is signed, a forged copy of
// a sample sent to its reader (the next sequence number, a byte changed), which ends an
// unsecured run, is dropped, and no topic or type name and no control sample is readable
// (docs/security.md#threat-model); a participant is refused a topic its permissions do not list;
// bad security files are one line naming the participant and the file, exit 2.

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <linux/if_ether.h>
#include <linux/if_packet.h>
#include <net/if.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <atomic>
#include <functional>
#include <map>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "climbsim/domain_lease.hpp"
#include "compose_file.hpp"
#include "launcher_run.hpp"
#include "security_material.hpp"

namespace {

using namespace climbsim::system_test;
namespace launcher = climbsim::launcher;

const std::string kScenario = "crack-descent --set duration_s=2";

/// A free domain id for a run the test starts on a domain it chose.
int freeDomain() {
  climbsim::DomainLease lease(150, 199);
  return lease.id();
}

struct Command {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr
};

/// Runs `command` through the shell with `env` ("K=V K=V ..." prefix), to its end.
Command runCommand(const std::string& env, const std::string& command, const std::string& tag) {
  const fs::path log = fs::path(CLIMBSIM_TEST_RUNS_DIR) / (tag + ".out");
  fs::create_directories(log.parent_path());
  const int status = std::system((env + " " + command + " > " + log.string() + " 2>&1").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(log)};
}

std::string outsider() { return std::string(CLIMBSIM_BIN_DIR) + "/climbsim-test-outsider"; }

std::string securityEnv(const fs::path& dir, const std::string& identity) {
  return "CLIMBSIM_DDS_SECURITY_DIR=" + dir.string() + " CLIMBSIM_DDS_SECURITY_IDENTITY=" + identity;
}

/// The value of "key=N" in an outsider's output, or -1.
long reported(const std::string& output, const std::string& key) {
  const auto at = output.find(key + "=");
  return at == std::string::npos ? -1 : std::stol(output.substr(at + key.size() + 1));
}

/// Security files made by the launcher's own code for the default composition on `domain`,
/// plus an "outsider" identity that may use the clock's topics.
fs::path makeMaterial(const std::string& tag, int domain) {
  const fs::path dir = fs::path(CLIMBSIM_TEST_RUNS_DIR) / tag;
  auto grants = launcher::securityGrants(launcher::loadComposeFile(std::string(CLIMBSIM_ROOT) + "/deploy/compose.yaml"));
  grants.push_back({"outsider", launcher::kLocalHost, {"clock/Stop"},
                    {"clock/RunStart", "clock/SimTime", "clock/StepDone"}});
  const char* path = std::getenv("PATH");
  launcher::makeSecurityMaterial(dir.string(), domain, grants, path ? path : "/usr/bin:/bin");
  return dir;
}

TEST(DdsSecurity, ASecuredRunGivesTheUnsecuredTraceAndOutsidersSeeNothing) {
  // The unsecured run, watched by an outsider: the control that the outsider does see a run.
  // Each outsider watches from before the run's start to its end (the test then makes the
  // outsider's --until-file).
  const fs::path done = fs::path(CLIMBSIM_TEST_RUNS_DIR) / "sec-run-ended";
  fs::create_directories(done.parent_path());
  fs::remove(done);
  const std::string watch = " --watch-s 300 --until-file " + done.string();
  const int open_domain = freeDomain();
  auto open_watch = std::async(std::launch::async, [&] {
    return runCommand("", outsider() + " --domain " + std::to_string(open_domain) + watch, "sec-open-watch");
  });
  const auto open = runScenario("sec-open", kScenario + " --domain " + std::to_string(open_domain));
  std::ofstream(done) << "ended\n";
  const Command open_seen = open_watch.get();
  fs::remove(done);
  ASSERT_EQ(open.exit_code, 0) << open.output;
  EXPECT_GT(reported(open_seen.output, "endpoints_seen"), 0) << open_seen.output;
  EXPECT_GT(reported(open_seen.output, "samples_seen"), 0) << open_seen.output;

  // The secured run, watched by an outsider without certificates and by one whose
  // certificate and permissions another CA signed.
  const int domain = freeDomain();
  const fs::path foreign = makeMaterial("sec-foreign-ca", domain);
  auto plain_watch = std::async(std::launch::async, [&] {
    return runCommand("", outsider() + " --domain " + std::to_string(domain) + watch, "sec-plain-watch");
  });
  auto foreign_watch = std::async(std::launch::async, [&] {
    return runCommand(securityEnv(foreign, "outsider"), outsider() + " --domain " + std::to_string(domain) + watch,
                      "sec-foreign-watch");
  });
  const auto secured = runScenario("sec-secured", kScenario + " --secure --domain " + std::to_string(domain));
  std::ofstream(done) << "ended\n";
  const Command plain_seen = plain_watch.get();
  const Command foreign_seen = foreign_watch.get();
  ASSERT_EQ(secured.exit_code, 0) << secured.output;
  EXPECT_TRUE(readFile(open.dir / "trace.csv") == readFile(secured.dir / "trace.csv"))
      << "the secured run's trace differs from the unsecured one";
  // Participant announcements (SPDP) stay in the clear, as DDS Security specifies: an outsider
  // learns that participants exist, but none of their readers and writers, and no sample.
  ASSERT_EQ(plain_seen.exit_code, 0) << plain_seen.output;
  EXPECT_GT(reported(plain_seen.output, "participants_seen"), 0) << "the outsider was not on the run's domain\n"
                                                                  << plain_seen.output;
  EXPECT_EQ(reported(plain_seen.output, "endpoints_seen"), 0) << plain_seen.output;
  EXPECT_EQ(reported(plain_seen.output, "samples_seen"), 0) << plain_seen.output;
  ASSERT_EQ(foreign_seen.exit_code, 0) << foreign_seen.output;
  EXPECT_EQ(reported(foreign_seen.output, "endpoints_seen"), 0) << foreign_seen.output;
  EXPECT_EQ(reported(foreign_seen.output, "samples_seen"), 0) << foreign_seen.output;
  EXPECT_GT(reported(foreign_seen.output, "unauthorized_participants"), 0)
      << "the run's participants and the foreign one never tried a handshake:\n" << foreign_seen.output;

  // The run's keys: 0600, and no CA key left to mint another identity with.
  const fs::path security = secured.dir / "security";
  EXPECT_TRUE(fs::exists(security / "thermo" / "identity.cert.pem"));
  EXPECT_EQ(fs::status(security / "thermo" / "identity.key.pem").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_FALSE(fs::exists(security / "ca.key.pem"));
  EXPECT_NE(secured.output.find("DDS Security on"), std::string::npos) << secured.output;
}

TEST(DdsSecurity, AParticipantIsRefusedATopicItsPermissionsDoNotList) {
  const int domain = freeDomain();
  const fs::path dir = makeMaterial("sec-permissions", domain);
  const std::string command = outsider() + " --domain " + std::to_string(domain) + " --only-write-stop";
  // The clock may write Stop: the same program with the clock's identity writes it.
  const Command clock = runCommand(securityEnv(dir, "clock"), command, "sec-permissions-clock");
  EXPECT_EQ(clock.exit_code, 0) << clock.output;
  EXPECT_NE(clock.output.find("sent stop"), std::string::npos) << clock.output;
  // thermo may read Stop but not write it.
  const Command thermo = runCommand(securityEnv(dir, "thermo"), command, "sec-permissions-thermo");
  EXPECT_EQ(thermo.exit_code, 2) << thermo.output;
  EXPECT_NE(thermo.output.find("participant 'thermo': its DDS Security permissions '" +
                               (dir / "thermo" / "permissions.p7s").string() +
                               "' do not let it publish topic 'clock/Stop'"),
            std::string::npos)
      << thermo.output;
  EXPECT_EQ(thermo.output.find("sent stop"), std::string::npos) << thermo.output;
}

/// A self-signed certificate for CN=`name` that expired an hour ago.
void writeExpiredCertificate(const fs::path& cert, const fs::path& key_file, const std::string& name) {
  EVP_PKEY* key = EVP_EC_gen("P-256");
  X509* x509 = X509_new();
  X509_set_version(x509, 2);
  ASN1_INTEGER_set(X509_get_serialNumber(x509), 1);
  X509_gmtime_adj(X509_getm_notBefore(x509), -7200);
  X509_gmtime_adj(X509_getm_notAfter(x509), -3600);
  X509_set_pubkey(x509, key);
  X509_NAME* subject = X509_get_subject_name(x509);
  X509_NAME_add_entry_by_txt(subject, "CN", MBSTRING_ASC, reinterpret_cast<const unsigned char*>(name.c_str()), -1, -1,
                             0);
  X509_set_issuer_name(x509, subject);
  X509_sign(x509, key, EVP_sha256());
  FILE* out = std::fopen(cert.c_str(), "w");
  PEM_write_X509(out, x509);
  std::fclose(out);
  out = std::fopen(key_file.c_str(), "w");
  PEM_write_PrivateKey(out, key, nullptr, nullptr, 0, nullptr, nullptr);
  std::fclose(out);
  X509_free(x509);
  EVP_PKEY_free(key);
}

TEST(DdsSecurity, BadSecurityFilesAreOneLineNamingTheParticipantAndTheFileExit2) {
  const int domain = freeDomain();
  const std::string clockctl = std::string(CLIMBSIM_BIN_DIR) + "/climbsim-clockctl --domain " +
                               std::to_string(domain) + " --timeout-s 1 pause";
  struct Case {
    std::string tag, file, expect;
    std::function<void(const fs::path&)> damage;
  };
  const std::vector<Case> cases = {
      {"missing-key", "identity.key.pem", "DDS Security private key '{}': cannot read it (No such file or directory)",
       [](const fs::path& own) { fs::remove(own / "identity.key.pem"); }},
      {"garbage-cert", "identity.cert.pem", "DDS Security certificate '{}': not a PEM certificate",
       [](const fs::path& own) { std::ofstream(own / "identity.cert.pem") << "not a certificate\n"; }},
      {"expired-cert", "identity.cert.pem", "DDS Security certificate '{}': the certificate has expired",
       [](const fs::path& own) {
         writeExpiredCertificate(own / "identity.cert.pem", own / "identity.key.pem", "climbsim-clockctl");
       }},
      {"missing-permissions", "permissions.p7s", "DDS Security permissions '{}': cannot read it",
       [](const fs::path& own) { fs::remove(own / "permissions.p7s"); }},
  };
  for (const auto& c : cases) {
    const fs::path dir = makeMaterial("sec-bad-" + c.tag, domain);
    const fs::path own = dir / "climbsim-clockctl";
    c.damage(own);
    const Command run = runCommand(securityEnv(dir, "climbsim-clockctl"), clockctl, "sec-bad-" + c.tag);
    EXPECT_EQ(run.exit_code, 2) << c.tag << ": " << run.output;
    std::string expect = c.expect;
    expect.replace(expect.find("{}"), 2, (own / c.file).string());
    EXPECT_NE(run.output.find("participant 'climbsim-clockctl': " + expect), std::string::npos)
        << c.tag << ": " << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << c.tag << ": one line\n" << run.output;
  }
}

TEST(DdsSecurity, ASecuredRunRefusesAServiceWithoutATopicTableBeforeAnythingStarts) {
  // The Python client (the PyPI cyclonedds wheel has no DDS Security): one line, exit 2.
  const auto run = runScenario("sec-python", kScenario + " --secure -f " + std::string(CLIMBSIM_ROOT) +
                                                 "/deploy/compose.python-controller.yaml");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("services.controller.command[0] = climbsim-py-controller: a Python client cannot join a "
                            "secured run"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(run.dir / "trace.csv")) << "something started";
  // The C client (Cyclone DDS 0.10's security plugins do not complete every handshake with
  // Fast DDS 2.9's: docs/deployment.md#dds-security): one line, exit 2.
  const auto c = runScenario("sec-c", kScenario + " --secure -f " + std::string(CLIMBSIM_ROOT) +
                                          "/deploy/compose.c-controller.yaml");
  EXPECT_EQ(c.exit_code, 2) << c.output;
  EXPECT_NE(c.output.find("services.valves.command[0] = climbsim-c-valves: the C client cannot join a secured run"),
            std::string::npos)
      << c.output;
}

// ---- across two hosts (network namespaces: root) ----

const char* const kLink = "csim-b-here";  // this side of the veth pair to the second host

/// Every frame on one interface while it lives (AF_PACKET), for a search of its bytes. Only
/// UDP datagrams to or from the ports of one DDS domain are kept (7400 + 250 d .. + 249: the
/// RTPS well-known ports), so that another run on the link cannot get in the way.
class PacketCapture {
 public:
  /// `forge`: once `forge_after` frames of the domain have passed, a copy of the next user
  /// sample that crosses the link whole (one unfragmented datagram) is sent again to its
  /// destination as a forgery: its sequence number one ahead (the sample the reader expects
  /// next, which it would take and whose real one it would then drop as a duplicate) and a byte
  /// of its data changed.
  PacketCapture(const std::string& interface, int domain, bool forge = false, std::size_t forge_after = 2000)
      : forge_(forge), forge_after_(forge_after), first_port_(7400 + 250 * domain),
        last_port_(7400 + 250 * domain + 249) {
    fd_ = ::socket(AF_PACKET, SOCK_RAW, htons(ETH_P_ALL));
    sockaddr_ll address{};
    address.sll_family = AF_PACKET;
    address.sll_protocol = htons(ETH_P_ALL);
    address.sll_ifindex = static_cast<int>(::if_nametoindex(interface.c_str()));
    ok_ = fd_ >= 0 && address.sll_ifindex > 0 &&
          ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
    if (ok_) thread_ = std::thread([this] { loop(); });
  }
  ~PacketCapture() { stop(); }
  /// Stops capturing; what was captured.
  const std::string& stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return bytes_;
  }
  bool ok() const { return ok_; }
  std::size_t frames() const { return frames_; }

 private:
  void loop() {
    std::vector<char> frame(65536);
    while (running_) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      const ssize_t n = ::recv(fd_, frame.data(), frame.size(), 0);
      const auto* f = reinterpret_cast<const unsigned char*>(frame.data());
      if (n > 0 && ofDomain(f, static_cast<std::size_t>(n))) {
        bytes_.append(frame.data(), static_cast<std::size_t>(n));
        ++frames_;
        classify(f, static_cast<std::size_t>(n));
        if (forge_ && !forged_ && frames_ > forge_after_) forged_ = forgeCopy(f, static_cast<std::size_t>(n));
      }
    }
  }
  /// An Ethernet frame of an IPv4 UDP datagram from or to a port of the domain.
  bool ofDomain(const unsigned char* f, std::size_t n) const {
    if (n < 14 + 20 + 8 || f[12] != 0x08 || f[13] != 0x00 || (f[14] >> 4) != 4 || f[23] != 17) return false;
    const std::size_t udp = 14 + 4 * static_cast<std::size_t>(f[14] & 0x0f);
    if (n < udp + 8) return false;
    const int source = f[udp] << 8 | f[udp + 1];
    const int destination = f[udp + 2] << 8 | f[udp + 3];
    auto in = [&](int port) { return port >= first_port_ && port <= last_port_; };
    return in(source) || in(destination);
  }
  /// Sends the forgery of the first user DATA submessage of `f` (see the constructor); false
  /// if `f` has none or is a fragment of a larger datagram.
  bool forgeCopy(const unsigned char* f, std::size_t n) {
    const bool fragment = (f[20] & 0x3f) != 0 || f[21] != 0;  // more fragments, or an offset
    const std::size_t udp = 14 + 4 * static_cast<std::size_t>(f[14] & 0x0f);
    const std::size_t udp_length = static_cast<std::size_t>(f[udp + 4]) << 8 | f[udp + 5];
    const std::size_t rtps = udp + 8;
    if (fragment || udp + udp_length != n || n < rtps + 24 || std::memcmp(f + rtps, "RTPS", 4) != 0) return false;
    std::vector<unsigned char> copy(f + rtps, f + n);
    for (std::size_t at = 20; at + 4 <= copy.size();) {
      const unsigned id = copy[at];
      const unsigned flags = copy[at + 1];
      const bool little = (flags & 1) != 0;
      const std::size_t length = little ? (copy[at + 2] | copy[at + 3] << 8) : (copy[at + 2] << 8 | copy[at + 3]);
      // A DATA with no inline QoS from a user writer (entity kind 0x02 or 0x03, not builtin).
      if (id == 0x15 && (flags & 0x02) == 0 && at + 4 + length <= copy.size() && length > 40 &&
          (copy[at + 15] == 0x02 || copy[at + 15] == 0x03)) {
        std::uint32_t low = 0;
        for (int k = 0; k < 4; ++k) low |= static_cast<std::uint32_t>(copy[at + 20 + k]) << (little ? 8 * k : 8 * (3 - k));
        ++low;
        for (int k = 0; k < 4; ++k) copy[at + 20 + k] = static_cast<unsigned char>(low >> (little ? 8 * k : 8 * (3 - k)));
        copy[at + 4 + length / 2 + 12] ^= 0x5a;  // a byte of the serialized data
        const int out = ::socket(AF_INET, SOCK_DGRAM, 0);
        sockaddr_in to{};
        to.sin_family = AF_INET;
        std::memcpy(&to.sin_addr, f + 30, 4);
        std::memcpy(&to.sin_port, f + udp + 2, 2);
        const bool sent = out >= 0 && ::sendto(out, copy.data(), copy.size(), 0, reinterpret_cast<sockaddr*>(&to),
                                               sizeof to) == static_cast<ssize_t>(copy.size());
        if (out >= 0) ::close(out);
        return sent;
      }
      if (length == 0) break;
      at += 4 + length;
    }
    return false;
  }

 public:
  /// Whether the forgery was sent.
  bool forged() const { return forged_; }

 private:
  bool forge_ = false, forged_ = false;
  std::size_t forge_after_ = 0;

  /// Sorts an RTPS message: signed as a whole (its first submessage SRTPS_PREFIX, 0x33:
  /// rtps_protection_kind SIGN) or made of protected submessages only (SEC_PREFIX, SEC_BODY,
  /// SEC_POSTFIX, 0x31 0x30 0x32, besides INFO_DST and INFO_TS: the key exchange, which DDS
  /// Security protects with the keys of the handshake, not the participant's); in the clear
  /// DDS Security leaves only participant announcements (SPDP, writer 0x000100c2) and the
  /// authentication handshake (participant stateless message, writer 0x000201c3).
  void classify(const unsigned char* f, std::size_t n) {
    const std::size_t udp = 14 + 4 * static_cast<std::size_t>(f[14] & 0x0f);
    const std::size_t rtps = udp + 8;
    const std::size_t end = std::min(n, udp + (static_cast<std::size_t>(f[udp + 4]) << 8 | f[udp + 5]));
    if (end < rtps + 24 || std::memcmp(f + rtps, "RTPS", 4) != 0) return;
    std::size_t at = rtps + 20;
    if (f[at] == 0x33) {
      ++signed_messages_;
      return;
    }
    std::string kinds;  // the submessage ids of the message, for the failure message
    bool clear = false;
    while (at + 4 <= end) {
      const unsigned id = f[at];
      char hex[8];
      std::snprintf(hex, sizeof hex, "%02x ", id);
      kinds += hex;
      const bool little = (f[at + 1] & 1) != 0;
      const std::size_t length = little ? (f[at + 2] | f[at + 3] << 8) : (f[at + 2] << 8 | f[at + 3]);
      if ((id == 0x15 || id == 0x16) && at + 16 <= end) {  // DATA, DATA_FRAG: writerId at +12
        const unsigned char* writer = f + at + 12;
        const bool spdp = writer[0] == 0x00 && writer[1] == 0x01 && writer[2] == 0x00 && writer[3] == 0xc2;
        const bool handshake = writer[0] == 0x00 && writer[1] == 0x02 && writer[2] == 0x01 && writer[3] == 0xc3;
        if (spdp || handshake) {
          ++announcements_;
          return;
        }
      }
      // ACKNACK, HEARTBEAT, GAP, NACK_FRAG, HEARTBEAT_FRAG, DATA, DATA_FRAG outside a SEC_BODY.
      clear = clear || id == 0x06 || id == 0x07 || id == 0x08 || id == 0x12 || id == 0x13 || id == 0x15 || id == 0x16;
      if (length == 0) break;
      at += 4 + length;
    }
    if (!clear) {
      ++signed_messages_;
      return;
    }
    ++unsigned_messages_;
    ++unsigned_kinds_[kinds];
  }

 public:
  std::size_t signedMessages() const { return signed_messages_; }
  std::size_t unsignedMessages() const { return unsigned_messages_; }
  std::size_t announcements() const { return announcements_; }
  /// The unsigned messages by their submessage ids ("0e 09 15 ": INFO_DST, INFO_TS, DATA).
  std::string unsignedKinds() const {
    std::string text;
    for (const auto& [kinds, count] : unsigned_kinds_) text += "[" + kinds + "] x" + std::to_string(count) + " ";
    return text;
  }

 private:
  std::size_t signed_messages_ = 0, unsigned_messages_ = 0, announcements_ = 0;
  std::map<std::string, std::size_t> unsigned_kinds_;
  int first_port_, last_port_;
  int fd_ = -1;
  bool ok_ = false;
  std::atomic<bool> running_{true};
  std::thread thread_;
  std::string bytes_;
  std::size_t frames_ = 0;
};

/// deploy/compose.two-hosts.yaml with its scenario path made absolute, and `security: on` if asked.
fs::path twoHostsCompose(bool secure) {
  std::string compose = readFile(fs::path(CLIMBSIM_ROOT) / "deploy" / "compose.two-hosts.yaml");
  const std::string from = "scenario: scenarios/";
  compose.replace(compose.find(from), from.size(), "scenario: " + std::string(CLIMBSIM_ROOT) + "/deploy/scenarios/");
  if (secure) compose.replace(compose.find("\nhosts:"), 1, "\nsecurity: on\n");
  const fs::path copy = fs::path(CLIMBSIM_TEST_RUNS_DIR) / (secure ? "compose.sec-two-hosts.yaml" : "compose.open-two-hosts.yaml");
  fs::create_directories(copy.parent_path());
  std::ofstream(copy) << compose;
  return copy;
}

TEST(DdsSecurity, TwoHostsSecuredSignEveryMessageDropAForgedSampleAndHideNamesAndControl) {
  if (::geteuid() != 0) GTEST_SKIP() << "network namespaces need root; run as root (CI does)";
  ASSERT_EQ(std::system((std::string(CLIMBSIM_ROOT) + "/deploy/climbsim hosts up").c_str()), 0);

  // What a DDS run sends in the clear: topic and type names in discovery (SEDP), the scenario
  // IDL file names in ParticipantReady samples. (Participant names, in the participant announcements, stay
  // in the clear in a secured run too, as DDS Security specifies.)
  const std::vector<std::string> plaintext = {"sealing/Leakage", "scene/DepthImage", "clock/StepGrant",
                                              "climbsim::Leakage", "clock.idl"};
  const int open_domain = freeDomain();
  PacketCapture open_capture(kLink, open_domain);
  ASSERT_TRUE(open_capture.ok()) << "no AF_PACKET capture on " << kLink;
  const auto open = runScenario("sec-two-hosts-open", kScenario + " --domain " + std::to_string(open_domain) + " -f " +
                                                         twoHostsCompose(false).string());
  const std::string open_bytes = open_capture.stop();
  ASSERT_EQ(open.exit_code, 0) << open.output;
  for (const auto& text : plaintext) {
    EXPECT_NE(open_bytes.find(text), std::string::npos) << "the capture of the unsecured run misses '" << text << "'";
  }

  // The unsecured run with the forgery of one of its samples sent to the reader: it takes it.
  // The forgery races the real sample it stands for and may land on a field the trace does
  // not show, so the control has three tries; one run the forgery changes is what it shows.
  bool forgery_took = false;
  for (int attempt = 1; attempt <= 3 && !forgery_took; ++attempt) {
    const int forged_domain = freeDomain();
    PacketCapture forged_capture(kLink, forged_domain, true);
    const auto forged_open = runScenario("sec-two-hosts-open-forged", kScenario + " --domain " +
                                                                       std::to_string(forged_domain) + " -f " +
                                                                       twoHostsCompose(false).string());
    forged_capture.stop();
    ASSERT_TRUE(forged_capture.forged()) << "no user sample crossed the link whole to forge";
    forgery_took =
        !(forged_open.exit_code == 0 && readFile(open.dir / "trace.csv") == readFile(forged_open.dir / "trace.csv"));
  }
  EXPECT_TRUE(forgery_took) << "the forged sample changed nothing in three unsecured runs: the forgery tells nothing";

  // The secured run, its link captured and the same forgery sent: it fails its signature check.
  const int domain = freeDomain();
  PacketCapture capture(kLink, domain, true);
  const auto secured = runScenario("sec-two-hosts", kScenario + " --domain " + std::to_string(domain) + " -f " +
                                                      twoHostsCompose(true).string());
  const std::string bytes = capture.stop();
  ASSERT_EQ(secured.exit_code, 0) << secured.output;
  EXPECT_TRUE(capture.forged()) << "no user sample crossed the link whole to forge";
  EXPECT_TRUE(readFile(open.dir / "trace.csv") == readFile(secured.dir / "trace.csv"))
      << "the secured two-host trace differs from the unsecured one: the forged sample was taken";
  // The shards on the second host read every depth image across the link: it was used.
  EXPECT_GT(bytes.size(), 2u * 100u * 16u * 1024u) << capture.frames() << " frames";
  for (const auto& text : plaintext) {
    EXPECT_EQ(bytes.find(text), std::string::npos) << "'" << text << "' crossed the link in the clear";
  }
  // docs/security.md#threat-model: every message but the announcements and the handshake is
  // signed (as a whole, or the key exchange submessage by submessage), so a forged or altered one (a sample, a heartbeat, a gap, an acknowledgement)
  // fails its check at the receiver and is dropped; the unsecured run signs none.
  EXPECT_GT(capture.signedMessages(), 100u);
  EXPECT_EQ(capture.unsignedMessages(), 0u) << capture.signedMessages() << " signed, " << capture.announcements()
                                            << " announcements and handshakes; unsigned: " << capture.unsignedKinds();
  EXPECT_EQ(open_capture.signedMessages(), 0u);
  EXPECT_GT(open_capture.unsignedMessages(), 100u);
  std::printf("two hosts: %zu bytes captured unsecured, %zu secured (%zu signed RTPS messages, %zu announcements and "
              "handshakes, %zu unsigned)\n",
              open_bytes.size(), bytes.size(), capture.signedMessages(), capture.announcements(),
              capture.unsignedMessages());
}

}  // namespace
