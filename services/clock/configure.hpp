#pragma once
/// @file
/// climbsim-clock's configuration (docs/design.md#configuration): the step and the end step of
/// a run from --step-ms and --duration-s (or --steps), which the launcher gives from the
/// scenario's step_ms and duration_s, and its timeouts. climbsim-clock's main and climbsim solo
/// both take the steps from here.

#include <chrono>
#include <cstdint>
#include <string>
#include <optional>

#include "climbsim/scenario.hpp"

namespace climbsim::clock {

/// A run's steps.
struct ClockTiming {
  std::int64_t dt_ns = 0;     ///< one step [ns]: round(step_ms 1e6)
  std::uint64_t end_step = 0;  ///< the steps to run: `steps`, else round(duration_s 1e9 / dt_ns)
};

/// The timing of --step-ms, --duration-s and --steps (exactly one of the last two).
/// ConfigError naming the option: a step that is not > 0 (or rounds to 0 ns), a duration that
/// is not > 0, neither a duration nor steps.
ClockTiming clockTiming(double step_ms, std::optional<double> duration_s, std::optional<std::uint64_t> steps);

/// A duration option's `seconds` [s] in whole milliseconds, rounded up (--start-timeout-s,
/// --step-timeout-s, --max-pause-s). ConfigError naming `option` unless it is finite and > 0.
std::chrono::milliseconds durationOption(const std::string& option, double seconds);

/// The timing of a scenario's run: clockTiming of the --step-ms and --duration-s the launcher
/// gives the clock for it (step_ns 1e-6 ms, duration_s).
ClockTiming scenarioClockTiming(const Scenario& scenario);

}  // namespace climbsim::clock
