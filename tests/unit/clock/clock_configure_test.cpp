// climbsim-clock's steps (services/clock/configure.hpp): its main takes them from --step-ms and
// --duration-s (or --steps), climbsim solo from the scenario the launcher gives those from.

#include <gtest/gtest.h>

#include <string>

#include "climbsim/errors.hpp"
#include "clock/configure.hpp"

namespace climbsim::clock {
namespace {

const std::string kScenarios = CLIMBSIM_SCENARIOS_DIR;

TEST(ClockConfigure, AScenariosStepsAreTheLaunchersOptions) {
  const Scenario scenario = loadScenario(kScenarios + "/crack-descent.yaml");  // step_ms 5, duration_s 20
  const ClockTiming solo = scenarioClockTiming(scenario);
  EXPECT_EQ(solo.dt_ns, 5'000'000);
  EXPECT_EQ(solo.end_step, 4000u);
  const ClockTiming main = clockTiming(5.0, 20.0, std::nullopt);  // --step-ms 5 --duration-s 20
  EXPECT_EQ(main.dt_ns, solo.dt_ns);
  EXPECT_EQ(main.end_step, solo.end_step);
}

TEST(ClockConfigure, StepsOrDurationAndBadValuesNamed) {
  EXPECT_EQ(clockTiming(2.5, std::nullopt, 7u).end_step, 7u);
  EXPECT_EQ(clockTiming(2.5, std::nullopt, 7u).dt_ns, 2'500'000);
  EXPECT_EQ(clockTiming(5.0, 0.012, std::nullopt).end_step, 2u);  // 12 ms of 5 ms steps, rounded
  auto message = [](double step_ms, std::optional<double> duration_s) -> std::string {
    try {
      clockTiming(step_ms, duration_s, std::nullopt);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(0.0, 1.0).find("--step-ms"), std::string::npos);
  EXPECT_NE(message(5.0, -1.0).find("--duration-s"), std::string::npos);
  EXPECT_NE(message(5.0, std::nullopt).find("--steps"), std::string::npos);
}

}  // namespace
}  // namespace climbsim::clock
