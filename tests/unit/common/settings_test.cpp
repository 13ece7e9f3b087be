#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include "climbsim/dds_context.hpp"
#include "climbsim/dds_settings.hpp"
#include "climbsim/domain_lease.hpp"
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

/// The shared-memory segment of the participant a context made [bytes] (0: none).
std::size_t segmentOf(DdsContext& context) {
  for (const auto& transport : context.participant()->get_qos().transport().user_transports) {
    if (const auto shm = std::dynamic_pointer_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor>(transport)) {
      return shm->segment_size();
    }
  }
  return 0;
}

TEST(DdsSettings, AProcessThatWritesImagesGetsASegmentForEightOfThemAndTheOthersTheQosFilesSmallOne) {
  const DomainLease domain(100, 199);  // as the tests' runs take theirs: no other participant on it
  DdsSettings small;
  small.domain_id = domain.id();
  small.resolve();  // the shipped QoS file
  DdsContext plain(small, "small-samples");
  const std::size_t base = segmentOf(plain);
  EXPECT_EQ(base, 4u << 20) << "deploy/qos/climbsim.xml's segment_size";

  DdsSettings images = small;
  images.largest_sample_bytes = imageSampleBytes(256, 256);
  DdsContext scene(images, "images-256");
  EXPECT_EQ(segmentOf(scene), base + kImagesInFlight * (256u * 256u * 4u + 65536u));
  images.largest_sample_bytes = imageSampleBytes(2048, 2048);
  DdsContext hires(images, "images-2048");
  EXPECT_GE(segmentOf(hires), kImagesInFlight * 2048u * 2048u * 4u) << "eight of the largest frames";
  EXPECT_EQ(segmentOf(plain), base) << "one process's segment is its own";
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
