#pragma once
/// @file
/// The clock's RunStart and Stop of a solo run, as run.mcap records them
/// (docs/recordings.md#what-runmcap-holds): a solo run has no clock, so they say what the
/// clock of the same run would (run_id 0, no window; the roster names and schedules only).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "climbsim/schedule.hpp"
#include "clock.h"

namespace climbsim::solo {

/// RunStart of a run of `end_step` steps of `dt_ns` [ns] with `roster` (name, schedule).
climbsim::RunStart soloRunStart(std::int64_t dt_ns, std::uint64_t end_step,
                                const std::vector<std::pair<std::string, Schedule>>& roster);

/// Stop after `steps` steps of `dt_ns` [ns]: last_step = steps - 1, t_ns = steps * dt_ns (the
/// clock's horizon), kind from `outcome` (completed, stopped, fell, else failed).
climbsim::Stop soloStop(std::uint64_t steps, std::int64_t dt_ns, const std::string& outcome,
                        const std::string& culprit, const std::string& reason);

}  // namespace climbsim::solo
