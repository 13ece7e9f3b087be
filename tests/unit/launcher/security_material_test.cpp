#include "security_material.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "climbsim/errors.hpp"
#include "climbsim/program_topics.hpp"
#include "climbsim/topic_catalog.hpp"

namespace climbsim::launcher {
namespace {

namespace fs = std::filesystem;

ComposeFile defaultCompose() { return loadComposeFile(std::string(CLIMBSIM_ROOT) + "/deploy/compose.yaml"); }

const SecurityGrant* grantOf(const std::vector<SecurityGrant>& grants, const std::string& identity) {
  for (const auto& g : grants) {
    if (g.identity == identity) return &g;
  }
  return nullptr;
}

bool has(const std::vector<std::string>& topics, const std::string& topic) {
  return std::find(topics.begin(), topics.end(), topic) != topics.end();
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ProgramTopics, EveryTopicIsInTheCatalog) {
  for (const auto& program : programTopics()) {
    for (const auto* list : {&program.writes, &program.reads}) {
      for (const auto& topic : *list) {
        const bool known = std::any_of(kTopicCatalog.begin(), kTopicCatalog.end(),
                                       [&](const TopicInfo& info) { return topic == info.name; });
        EXPECT_TRUE(known) << program.program << ": " << topic << " is not in climbsim/topic_catalog.hpp";
      }
    }
  }
}

TEST(ProgramTopics, EveryWrittenTopicHasAReaderInTheTable) {
  // A topic some program writes and none reads would be a grant nobody needs; the laser
  // scans are for controllers of your own (none of climbsim's programs reads them).
  auto table = programTopics();
  table.push_back(lockstepTopics());
  for (const auto& info : kTopicCatalog) {
    if (std::string(info.name) == topic::kLaserScan) continue;
    bool written = false, read = false;
    for (const auto& program : table) {
      written |= has(program.writes, info.name);
      read |= has(program.reads, info.name);
    }
    if (written) {
      EXPECT_TRUE(read) << info.name << " is written but read by no program of the table";
    }
  }
}

TEST(SecurityGrants, EveryRosterInstanceTheClockAndClockctlGetTheirProgramsTopics) {
  const ComposeFile compose = defaultCompose();
  const auto grants = securityGrants(compose);
  for (const auto& name : compose.roster()) {
    const SecurityGrant* grant = grantOf(grants, name);
    ASSERT_NE(grant, nullptr) << name;
    EXPECT_TRUE(has(grant->writes, topic::kStepDone)) << name;
    EXPECT_TRUE(has(grant->reads, topic::kStepGrant)) << name;
    EXPECT_FALSE(has(grant->writes, topic::kStop)) << name << " may not stop the run";
    EXPECT_FALSE(has(grant->writes, topic::kClockControl)) << name << " may not control the clock";
  }
  const SecurityGrant* thermo = grantOf(grants, "thermo");
  ASSERT_NE(thermo, nullptr);
  EXPECT_TRUE(has(thermo->writes, topic::kChamberState));
  EXPECT_TRUE(has(thermo->reads, topic::kValveCommand));
  EXPECT_FALSE(has(thermo->writes, topic::kValveCommand));
  const SecurityGrant* clock = grantOf(grants, "clock");
  ASSERT_NE(clock, nullptr);
  EXPECT_TRUE(has(clock->writes, topic::kStop));
  EXPECT_TRUE(has(clock->reads, topic::kClockControl));
  const SecurityGrant* clockctl = grantOf(grants, "climbsim-clockctl");
  ASSERT_NE(clockctl, nullptr);
  EXPECT_EQ(clockctl->writes, std::vector<std::string>{topic::kClockControl});
  // The viewer is an observer: it reads, writes only ClockControl, never StepDone.
  const SecurityGrant* viewer = grantOf(grants, "viewer");
  ASSERT_NE(viewer, nullptr);
  EXPECT_FALSE(has(viewer->writes, topic::kStepDone));
}

TEST(SecurityGrants, APythonClientIsRefusedNamingTheService) {
  const ComposeFile compose =
      loadComposeFile(std::string(CLIMBSIM_ROOT) + "/deploy/compose.python-controller.yaml");
  try {
    securityGrants(compose);
    FAIL() << "a Python participant was granted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("services.controller"), std::string::npos) << what;
    EXPECT_NE(what.find("Python"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

TEST(SecurityDocuments, GovernanceSignsEveryMessageEncryptsDiscoveryAndAdmitsNoUnauthenticatedParticipant) {
  const std::string xml = governanceXml(42);
  EXPECT_NE(xml.find("<id>42</id>"), std::string::npos);
  EXPECT_NE(xml.find("<allow_unauthenticated_participants>false<"), std::string::npos);
  EXPECT_NE(xml.find("<enable_join_access_control>true<"), std::string::npos);
  EXPECT_NE(xml.find("<rtps_protection_kind>SIGN<"), std::string::npos);
  EXPECT_NE(xml.find("<discovery_protection_kind>ENCRYPT<"), std::string::npos);
  EXPECT_EQ(xml.find("<enable_read_access_control>false<"), std::string::npos);
  EXPECT_EQ(xml.find("<enable_write_access_control>false<"), std::string::npos);
  EXPECT_EQ(xml.find("<enable_discovery_protection>false<"), std::string::npos);
  // One rule per protection, in order: the first that matches a topic decides.
  std::size_t at = 0;
  for (const auto& rule : topicProtections()) {
    at = xml.find("<topic_expression>" + rule.expression + "</topic_expression>", at);
    ASSERT_NE(at, std::string::npos) << rule.expression;
    const auto data = xml.find("<data_protection_kind>", at);
    EXPECT_EQ(xml.substr(data, xml.find('<', data + 1) - data), "<data_protection_kind>" + rule.data) << rule.expression;
  }
}

TEST(SecurityDocuments, TheClocksTopicsAndRecordBatchesAreEncryptedStepDataOnlySigned) {
  // docs/security.md#per-topic-protection: the control plane and the batches (they name topics)
  // secret, the step data authentic only.
  for (const auto& info : kTopicCatalog) {
    const std::string name = info.name;
    const bool secret = name.rfind("clock/", 0) == 0 || name.rfind("record/", 0) == 0;
    const std::string expected = secret ? "ENCRYPT" : "NONE";
    EXPECT_EQ(protectionOf(name).data, expected) << name;
  }
  EXPECT_EQ(protectionOf(topic::kStepGrant).data, "ENCRYPT");
  EXPECT_EQ(protectionOf(topic::kClockControl).data, "ENCRYPT");
  EXPECT_EQ(protectionOf(topic::kRecordBatch).data, "ENCRYPT");
  EXPECT_EQ(protectionOf(topic::kDepthImage).data, "NONE");
  EXPECT_EQ(topicProtections().back().expression, "*") << "the last rule covers every topic";
}

TEST(SecurityDocuments, PermissionsListExactlyTheGrantedTopics) {
  const SecurityGrant grant{"thermo", kLocalHost, {"thermo/ChamberState"}, {"sealing/Leakage", "clock/Stop"}};
  const std::string xml = permissionsXml(grant, 7, 30);
  const auto publish = xml.substr(xml.find("<publish>"), xml.find("</publish>") - xml.find("<publish>"));
  const auto subscribe = xml.substr(xml.find("<subscribe>"), xml.find("</subscribe>") - xml.find("<subscribe>"));
  EXPECT_NE(publish.find("<topic>thermo/ChamberState</topic>"), std::string::npos);
  EXPECT_EQ(publish.find("sealing/Leakage"), std::string::npos);
  EXPECT_NE(subscribe.find("<topic>clock/Stop</topic>"), std::string::npos);
  EXPECT_NE(xml.find("<subject_name>CN=thermo</subject_name>"), std::string::npos);
  EXPECT_NE(xml.find("<default>DENY</default>"), std::string::npos);
  EXPECT_NE(xml.find("<id>7</id>"), std::string::npos);
}

TEST(SecurityMaterial, SignedFilesVerifyAgainstTheRunCaWhoseKeyIsGone) {
  char pattern[] = "/tmp/climbsim-security-test-XXXXXX";
  ASSERT_NE(::mkdtemp(pattern), nullptr);
  const fs::path dir = fs::path(pattern) / "security";
  const std::vector<SecurityGrant> grants = {{"clock", kLocalHost, {"clock/Stop"}, {"clock/StepDone"}},
                                             {"thermo", kLocalHost, {"clock/StepDone"}, {"clock/Stop"}}};
  const char* path = std::getenv("PATH");
  makeSecurityMaterial(dir.string(), 3, grants, path ? path : "/usr/bin:/bin");

  EXPECT_FALSE(fs::exists(dir / "ca.key.pem")) << "the CA's key stays after signing";
  struct stat info {};
  ASSERT_EQ(::stat((dir / "thermo" / "identity.key.pem").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  ASSERT_EQ(::stat(dir.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0700u);
  const std::string ca = (dir / "ca.cert.pem").string();
  const std::string verify_cert = "openssl verify -CAfile " + ca + " " + (dir / "thermo" / "identity.cert.pem").string() +
                                  " > /dev/null 2>&1";
  EXPECT_EQ(std::system(verify_cert.c_str()), 0) << "thermo's certificate is not signed by the run CA";
  const fs::path out = dir / "verified.xml";
  const std::string verify_permissions = "openssl smime -verify -in " + (dir / "thermo" / "permissions.p7s").string() +
                                         " -CAfile " + ca + " -out " + out.string() + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(verify_permissions.c_str()), 0) << "thermo's permissions do not verify";
  EXPECT_NE(readAll(out).find("<subject_name>CN=thermo</subject_name>"), std::string::npos);
  const std::string subject = "openssl x509 -noout -subject -in " + (dir / "thermo" / "identity.cert.pem").string() +
                              " > " + (dir / "subject.txt").string();
  ASSERT_EQ(std::system(subject.c_str()), 0);
  EXPECT_NE(readAll(dir / "subject.txt").find("CN = thermo"), std::string::npos);
  fs::remove_all(pattern);
}

}  // namespace
}  // namespace climbsim::launcher
