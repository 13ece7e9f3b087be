#include "valve_actuator.hpp"

#include <algorithm>
#include <limits>

namespace climbsim::thermo {

void queueValveCommands(ThermoState& state, const std::vector<double>& command,
                        std::int64_t activation_t_ns) {
  auto& queue = state.pending_valve_commands;
  const std::size_t queued = queue.size();
  const int valves = static_cast<int>(command.size());
  for (int c = 0; c < valves; ++c) {
    double last = state.valve_target[c];
    for (std::size_t i = queued; i-- > 0;) {
      if (queue[i].chamber == c) {
        last = queue[i].opening;
        break;
      }
    }
    if (command[c] != last) queue.push_back({activation_t_ns, c, command[c]});
  }
}

void applyDueValveCommands(ThermoState& state, std::int64_t t_ns) {
  auto& queue = state.pending_valve_commands;
  // Activation times are pushed in non-decreasing order (t_ns + a fixed delay), so the due
  // commands form a prefix.
  auto due_end = queue.begin();
  while (due_end != queue.end() && due_end->activation_t_ns <= t_ns) {
    state.valve_target[due_end->chamber] = due_end->opening;
    ++due_end;
  }
  queue.erase(queue.begin(), due_end);
}

std::int64_t nextValveActivationNs(const ThermoState& state) {
  return state.pending_valve_commands.empty() ? std::numeric_limits<std::int64_t>::max()
                                              : state.pending_valve_commands.front().activation_t_ns;
}

}  // namespace climbsim::thermo
