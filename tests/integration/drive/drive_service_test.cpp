// climbsim-drive with the real clock and a feeder process on real Fast DDS.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "lockstep_harness.hpp"

namespace climbsim::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kSteps = 300;  // 1.5 s of simulated time at 5 ms

struct RobotTrace {
  std::string record;
  std::vector<std::array<double, 3>> position_m;  ///< RobotState.position_m in step order
  std::vector<bool> fell;
  std::vector<double> normal_sum_n;               ///< sum of DriveState normal forces
};

/// clock + climbsim-drive + a feeder that holds the robot with `downforce` N and records it.
RobotTrace runDrive(const std::string& tag, const std::string& downforce) {
  LockstepRun run(tag);
  run.startClock("drive,feeder", {"--steps", std::to_string(kSteps), "--step-ms", "5"});
  run.start("drive", "climbsim-drive", {"--name", "drive"});
  run.start("feeder", "climbsim-test-drive-feeder",
            {"--name", "feeder", "--downforce", downforce, "--record", (run.dir() / "feeder.rec").string()});
  const auto codes = run.waitAll(180s);
  for (const auto& name : {"clock", "drive", "feeder"}) {
    EXPECT_EQ(codes.count(name) ? codes.at(name) : -1, 0) << name << "\n" << run.allLogs();
  }
  RobotTrace trace;
  trace.record = run.record("feeder");
  std::istringstream lines(trace.record);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string step, kind, source, stamp, t_ns;
    int fell = 0;
    fields >> step >> kind >> source >> stamp >> t_ns >> fell;
    if (kind == "robot") {
      std::string x, y, z;
      fields >> x >> y >> z;
      trace.position_m.push_back(
          {std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr), std::strtod(z.c_str(), nullptr)});
      trace.fell.push_back(fell != 0);
    } else if (kind == "wheels") {
      double sum = 0.0;
      std::string v[4];
      while (fields >> v[0] >> v[1] >> v[2] >> v[3]) sum += std::strtod(v[2].c_str(), nullptr);
      trace.normal_sum_n.push_back(sum);
    }
  }
  return trace;
}

TEST(DriveService, WithTheDesiredDownforceTheRobotHoldsOnAVerticalWall) {
  const auto trace = runDrive("drive-holds", "2200");
  ASSERT_EQ(trace.position_m.size(), static_cast<std::size_t>(kSteps - 1)) << trace.record.substr(0, 2000);
  const auto& first = trace.position_m.front();
  const auto& last = trace.position_m.back();
  EXPECT_LT(std::hypot(last[0] - first[0], last[1] - first[1]), 5e-3);
  EXPECT_FALSE(trace.fell.back());
  ASSERT_FALSE(trace.normal_sum_n.empty());
  EXPECT_NEAR(trace.normal_sum_n.back(), 2200.0, 22.0);  // the wheels carry the adhesion force
}

TEST(DriveService, WithoutDownforceTheRobotFallsOffAVerticalWall) {
  const auto trace = runDrive("drive-falls", "0");
  ASSERT_EQ(trace.fell.size(), static_cast<std::size_t>(kSteps - 1)) << trace.record.substr(0, 2000);
  EXPECT_FALSE(trace.fell.front());
  EXPECT_TRUE(trace.fell.back());
  EXPECT_LT(trace.position_m.back()[1], -0.05);  // on its way down
}

}  // namespace
}  // namespace climbsim::testing
