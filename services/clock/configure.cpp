#include "configure.hpp"

#include <cmath>
#include <string>

#include "climbsim/errors.hpp"

namespace climbsim::clock {

ClockTiming clockTiming(double step_ms, std::optional<double> duration_s, std::optional<std::uint64_t> steps) {
  ClockTiming timing;
  const double ns = std::round(step_ms * 1e6);
  if (!std::isfinite(step_ms) || ns < 1.0 || ns > 9.2e18) {
    throw ConfigError("--step-ms = " + std::to_string(step_ms) + "; it must be > 0");
  }
  timing.dt_ns = static_cast<std::int64_t>(ns);
  if (steps) {
    timing.end_step = *steps;
  } else if (duration_s) {
    if (!std::isfinite(*duration_s) || *duration_s <= 0) {
      throw ConfigError("--duration-s = " + std::to_string(*duration_s) + "; it must be > 0");
    }
    timing.end_step = static_cast<std::uint64_t>(std::llround(*duration_s * 1e9 / static_cast<double>(timing.dt_ns)));
  } else {
    throw ConfigError("give --duration-s or --steps");
  }
  return timing;
}

std::chrono::milliseconds durationOption(const std::string& option, double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0) {
    throw ConfigError(option + " = " + std::to_string(seconds) + "; it must be > 0");
  }
  return std::chrono::milliseconds(static_cast<std::int64_t>(std::ceil(seconds * 1000.0)));
}

ClockTiming scenarioClockTiming(const Scenario& scenario) {
  return clockTiming(static_cast<double>(scenario.step_ns) * 1e-6, scenario.duration_s, std::nullopt);
}

}  // namespace climbsim::clock
