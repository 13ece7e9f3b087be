#pragma once
/// @file
/// Valve command delay: a queue of stamped commands on the model's own time axis.
/// (The rate limit is applied by ThermoModel::step, which cuts its integration at the
/// instants a valve reaches its target so that openings are linear in time within an
/// integration interval.)

#include <vector>
#include <cstdint>

#include "thermo_types.hpp"

namespace climbsim::thermo {

/// Queues command[c] for each valve c (command.size() valves) to become its target at
/// activation_t_ns, unless it equals the last command queued for that valve (or, with none
/// queued, the target in force): a held command then adds nothing, and the queue stays at
/// most delay / step + 1 entries per valve.
void queueValveCommands(ThermoState& state, const std::vector<double>& command,
                        std::int64_t activation_t_ns);

/// Makes every pending command with activation_t_ns <= t_ns the target of its valve, in
/// order, and removes it from the queue.
void applyDueValveCommands(ThermoState& state, std::int64_t t_ns);

/// Activation time of the earliest pending command [ns], or INT64_MAX if none.
std::int64_t nextValveActivationNs(const ThermoState& state);

}  // namespace climbsim::thermo
