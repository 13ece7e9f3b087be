// climbsim-thermo with the real clock and feeder processes on real Fast DDS.

#include <gtest/gtest.h>

#include <cstdlib>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kSteps = 1000;  // 5 s of simulated time at 5 ms: ten engine lags

struct ThermoTrace {
  std::string record;               ///< the feeder's record: every ChamberState and AdhesionForce read
  std::vector<double> downforce_n;  ///< AdhesionForce.downforce_n in step order
};

/// clock + climbsim-thermo + a feeder (engines on, valves open, leak areas `leak_scale` times
/// the basic leakage) that records thermo's outputs; with `sharded`, a second feeder publishes
/// the odd-numbered leakage segments and the first one the even-numbered ones.
ThermoTrace runThermo(const std::string& tag, bool sharded, const std::string& leak_scale) {
  LockstepRun run(tag);
  run.startClock(sharded ? "thermo,feeder,feeder2" : "thermo,feeder",
                 {"--steps", std::to_string(kSteps), "--step-ms", "5"});
  run.start("thermo", "climbsim-thermo", {"--name", "thermo"});
  run.start("feeder", "climbsim-test-thermo-feeder",
            {"--name", "feeder", "--commands", "--leakage", sharded ? "0/2" : "all", "--leak-scale", leak_scale,
             "--record", (run.dir() / "feeder.rec").string()});
  if (sharded) {
    run.start("feeder2", "climbsim-test-thermo-feeder",
              {"--name", "feeder2", "--leakage", "1/2", "--leak-scale", leak_scale});
  }
  const auto codes = run.waitAll(180s);
  std::vector<std::string> names = {"clock", "thermo", "feeder"};
  if (sharded) names.push_back("feeder2");
  for (const auto& name : names) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  ThermoTrace trace;
  trace.record = run.record("feeder");
  std::istringstream lines(trace.record);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string step, kind, source, stamp, t_ns, force;
    fields >> step >> kind >> source >> stamp >> t_ns;
    if (kind != "force") continue;
    fields >> force;
    trace.downforce_n.push_back(std::strtod(force.c_str(), nullptr));
  }
  return trace;
}

TEST(ThermoService, DownforceRisesMonotonicallyToASteadyValue) {
  const auto whole = runThermo("thermo-basic", false, "1");
  // Read at steps 1..kSteps-1: the outputs of steps 0..kSteps-2.
  ASSERT_EQ(whole.downforce_n.size(), static_cast<std::size_t>(kSteps - 1)) << whole.record.substr(0, 2000);
  const auto& f = whole.downforce_n;
  for (std::size_t k = 1; k < f.size(); ++k) {
    ASSERT_GE(f[k], f[k - 1]) << "downforce fell at step " << k;
  }
  const double last = f.back();
  EXPECT_GT(last, 500.0);
  // Settled: the last 100 steps (0.5 s) change it by less than 0.1 %.
  EXPECT_LT(last - f[f.size() - 101], 1e-3 * last);
}

TEST(ThermoService, LeakageFromTwoShardsGivesTheUnshardedChamberStatesBitForBit) {
  // Three times the basic leakage, so that thermo's default (basic leakage) cannot pass for
  // merged input: the leak must reach the model and lower the downforce.
  const auto whole = runThermo("thermo-unsharded", false, "3");
  const auto sharded = runThermo("thermo-sharded", true, "3");
  const auto basic = runThermo("thermo-basic-reference", false, "1");
  ASSERT_EQ(whole.downforce_n.size(), static_cast<std::size_t>(kSteps - 1));
  ASSERT_EQ(basic.downforce_n.size(), whole.downforce_n.size());
  EXPECT_LT(whole.downforce_n.back(), 0.99 * basic.downforce_n.back());
  EXPECT_TRUE(sharded.record == whole.record) << "the sharded run recorded different thermo outputs";
}

}  // namespace
}  // namespace climbsim::testing
