// The adhesion loop as separate processes on real Fast DDS: climbsim-clock, climbsim-thermo,
// climbsim-controller (reference controller of the default scenario) and climbsim-recorder.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kSteps = 1600;  // 8 s at 5 ms

struct Trace {
  std::string text;                    ///< trace.csv as written
  std::vector<double> downforce_n;     ///< per row
  std::string summary;                 ///< summary.json
};

Trace runLoop(const std::string& tag, const std::vector<std::string>& controller_sets = {}) {
  LockstepRun run(tag);
  run.startClock("thermo,controller,recorder", {"--steps", std::to_string(kSteps), "--step-ms", "5"});
  run.start("thermo", "climbsim-thermo", {"--name", "thermo", "--inputs", "valves,engines"});
  std::vector<std::string> controller_args = {"--name", "controller"};
  for (const auto& s : controller_sets) controller_args.insert(controller_args.end(), {"--set", s});
  run.start("controller", "climbsim-controller", controller_args);
  run.start("recorder", "climbsim-recorder",
            {"--name", "recorder", "--inputs", "chamber,adhesion", "--out", (run.dir() / "out").string()});
  const auto codes = run.waitAll(240s);
  for (const char* name : {"clock", "thermo", "controller", "recorder"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  Trace trace;
  trace.text = readFile(run.dir() / "out" / "trace.csv");
  trace.summary = readFile(run.dir() / "out" / "summary.json");
  std::istringstream lines(trace.text);
  std::string line;
  std::getline(lines, line);  // header
  EXPECT_EQ(line.rfind("t_s,downforce_n,pf_x_m,pf_y_m,p1_pa", 0), 0u) << line;
  while (std::getline(lines, line)) {
    const auto first = line.find(',');
    trace.downforce_n.push_back(std::strtod(line.c_str() + first + 1, nullptr));
  }
  return trace;
}

TEST(AdhesionLoop, ReferenceControllerHoldsTheSetPointAndTheTraceRepeatsBitForBit) {
  const auto first = runLoop("loop-reference-1");
  ASSERT_EQ(first.downforce_n.size(), static_cast<std::size_t>(kSteps)) << first.text.substr(0, 1000);
  // The last 2 s: within 1 % of the default scenario's 2200 N.
  for (std::size_t k = first.downforce_n.size() - 400; k < first.downforce_n.size(); ++k) {
    ASSERT_NEAR(first.downforce_n[k], 2200.0, 22.0) << "row " << k;
  }
  EXPECT_NE(first.summary.find("\"completed\": true"), std::string::npos) << first.summary;
  const auto second = runLoop("loop-reference-2");
  EXPECT_TRUE(first.text == second.text) << "the same scenario gave a different trace";
}

TEST(AdhesionLoop, ClosedValvesGiveNoDownforceAndALowerSetPointLess) {
  const auto closed = runLoop("loop-none", {"controller={type: none}"});
  ASSERT_EQ(closed.downforce_n.size(), static_cast<std::size_t>(kSteps));
  // Valves closed: the chambers stay at ambient, whatever the engines do to the reservoir.
  EXPECT_LT(std::abs(closed.downforce_n.back()), 1.0);
  const auto low = runLoop("loop-1500", {"controller.downforce_n=1500"});
  ASSERT_EQ(low.downforce_n.size(), static_cast<std::size_t>(kSteps));
  EXPECT_NEAR(low.downforce_n.back(), 1500.0, 15.0);
}

}  // namespace
}  // namespace climbsim::testing
