// Bad command lines: one line naming the thing, a non-zero exit, no hang.

#include <gtest/gtest.h>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

struct Outcome {
  int code;
  std::string output;
};

Outcome runOnce(const std::string& tag, const std::string& exe, std::vector<std::string> args, bool with_domain = true) {
  LockstepRun run(tag);
  if (with_domain) {
    run.start("p", exe, args);
  } else {
    ProcessSpec spec;
    spec.argv.push_back(std::string(CLIMBSIM_BIN_DIR) + "/" + exe);
    spec.argv.insert(spec.argv.end(), args.begin(), args.end());
    spec.output_file = (run.dir() / "p.log").string();
    spec.env["CLIMBSIM_DOMAIN"] = "";
    ChildProcess child(spec);
    const auto code = child.waitFor(20s);
    return {code.value_or(-1), run.log("p")};
  }
  const auto code = run.process("p").waitFor(20s);
  return {code.value_or(-1), run.log("p")};
}

/// One line of error output (plus nothing else of substance).
int errorLines(const std::string& output) {
  int lines = 0;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) lines += line.find("error") != std::string::npos ? 1 : 0;
  return lines;
}

TEST(BadInput, DuplicateRosterName) {
  const auto out = runOnce("dup", "climbsim-clock", {"--roster", "a,b,a", "--steps", "10"});
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("participant 'a' is named twice"), std::string::npos) << out.output;
  EXPECT_EQ(errorLines(out.output), 1) << out.output;
}

TEST(BadInput, ZeroPeriod) {
  const auto out = runOnce("period0", "climbsim-test-participant", {"--name", "a", "--period", "0"});
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("participant 'a': period_steps = 0"), std::string::npos) << out.output;
}

TEST(BadInput, DomainOutOfRange) {
  const auto out = runOnce("domain", "climbsim-clock", {"--roster", "a", "--steps", "10", "--domain", "300"}, false);
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("--domain = 300 is out of range"), std::string::npos) << out.output;
}

TEST(BadInput, MissingDomain) {
  const auto out = runOnce("nodomain", "climbsim-clock", {"--roster", "a", "--steps", "10"}, false);
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("no DDS domain id"), std::string::npos) << out.output;
}

TEST(BadInput, UnreadableQosFile) {
  const auto out = runOnce("qos", "climbsim-clock", {"--roster", "a", "--steps", "10", "--qos", "/nonexistent/q.xml"});
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("'/nonexistent/q.xml': cannot read the QoS profile file"), std::string::npos)
      << out.output;
}

TEST(BadInput, QosFileThatIsNotAProfile) {
  LockstepRun run("qosbad");
  const auto bad = run.dir() / "bad.xml";
  std::ofstream(bad) << "<dds><profiles><participant profile_name='x'><rtps><nonsense/></rtps></participant>";
  run.start("p", "climbsim-clock", {"--roster", "a", "--steps", "10", "--qos", bad.string()});
  const auto code = run.process("p").waitFor(20s);
  EXPECT_EQ(code.value_or(-1), 2);
  EXPECT_NE(run.log("p").find("bad.xml"), std::string::npos) << run.log("p");
}

TEST(BadInput, BadParticipantName) {
  const auto out = runOnce("name", "climbsim-test-participant", {"--name", "my robot"});
  EXPECT_EQ(out.code, 2);
  EXPECT_NE(out.output.find("'my robot' has the character ' '"), std::string::npos) << out.output;
}

}  // namespace
}  // namespace climbsim::testing
