#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "climbsim/dds_settings.hpp"
#include "climbsim/errors.hpp"
#include "climbsim/names.hpp"

namespace climbsim {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(DdsSettings, DomainIdRange) {
  EXPECT_EQ(parseDomainId("--domain", "0"), 0);
  EXPECT_EQ(parseDomainId("--domain", "232"), 232);
  EXPECT_NE(messageOf([] { parseDomainId("--domain", "233"); }).find("--domain = 233 is out of range"),
            std::string::npos);
  EXPECT_NE(messageOf([] { parseDomainId("CLIMBSIM_DOMAIN", "-1"); }).find("CLIMBSIM_DOMAIN = -1"), std::string::npos);
  EXPECT_NE(messageOf([] { parseDomainId("--domain", "7x"); }).find("not an integer"), std::string::npos);
  EXPECT_THROW(parseDomainId("--domain", ""), ConfigError);
}

TEST(DdsSettings, UnreadableQosFileIsNamed) {
  DdsSettings s;
  s.domain_id = 5;
  s.qos_file = "/nonexistent/qos.xml";
  EXPECT_NE(messageOf([&] { s.resolve(); }).find("'/nonexistent/qos.xml': cannot read"), std::string::npos);
}

TEST(DdsSettings, DomainFromEnvironment) {
  ::setenv("CLIMBSIM_DOMAIN", "17", 1);
  DdsSettings s;
  s.resolve();
  EXPECT_EQ(s.domain_id, 17);
  ::setenv("CLIMBSIM_DOMAIN", "999", 1);
  DdsSettings bad;
  EXPECT_NE(messageOf([&] { bad.resolve(); }).find("CLIMBSIM_DOMAIN = 999"), std::string::npos);
  ::unsetenv("CLIMBSIM_DOMAIN");
  DdsSettings none;
  EXPECT_NE(messageOf([&] { none.resolve(); }).find("no DDS domain id"), std::string::npos);
}

TEST(Names, Validation) {
  EXPECT_NO_THROW(validateName("--name", "sealing-1.shard_2"));
  EXPECT_NE(messageOf([] { validateName("--name", "a b"); }).find("'a b' has the character ' '"), std::string::npos);
  EXPECT_THROW(validateName("--name", std::string(64, 'a')), ConfigError);
  EXPECT_THROW(validateName("--name", ""), ConfigError);
  EXPECT_EQ(parseNameList("--roster", "a,b,c"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_THROW(parseNameList("--roster", "a,,c"), ConfigError);
}

}  // namespace
}  // namespace climbsim

TEST(Names, OneInputsParserForEveryService) {
  const std::vector<std::string> choices{"leakage", "valves", "engines"};
  EXPECT_EQ(climbsim::parseChoiceList("--inputs", "valves,leakage", choices),
            (std::set<std::string>{"leakage", "valves"}));
  EXPECT_TRUE(climbsim::parseChoiceList("--inputs", "none", choices).empty());
  try {
    climbsim::parseChoiceList("--inputs", "leakage,pressure", choices);
    FAIL() << "an unknown input was taken";
  } catch (const climbsim::ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "--inputs = 'leakage,pressure': unknown input 'pressure' (choose from leakage, valves, engines, or none)");
  }
  EXPECT_THROW(climbsim::parseChoiceList("--inputs", "leakage,,valves", choices), climbsim::ConfigError);
}
