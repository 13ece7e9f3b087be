#pragma once
/// @file
/// The commands of a recorded run that a `recorded` controller plays back open-loop
/// (docs/recordings.md#replaying-commands): each command holds from the step it was computed at
/// until the next recorded one, as the run's thermo held it. No DDS, no files: the controller's
/// configuration reads them from run.mcap (recorded_commands_file.hpp).

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace climbsim::controller {

/// A ValveCommand as it travelled.
struct RecordedValveCommand {
  std::int64_t t_ns = 0;              ///< the step it was computed at [ns]
  std::vector<double> opening;        ///< valves of chambers 1..N, 0..1
  double downforce_setpoint_n = 0.0;  ///< the recorded controller's F* [N]; 0: none
};

/// An EngineCommand as it travelled, each engine's speed target (on ? speed : 0, what the
/// engine's lag follows).
struct RecordedEngineCommand {
  std::int64_t t_ns = 0;      ///< the step it was computed at [ns]
  std::vector<double> speed;  ///< per engine, 0..1
};

/// A recorded run's commands, each list in increasing t_ns.
struct RecordedCommands {
  std::string file;                             ///< the run.mcap they came from
  std::vector<RecordedValveCommand> valves;     ///< empty: the run commanded none
  std::vector<RecordedEngineCommand> engines;   ///< empty: the run commanded none
  std::int64_t end_ns = 0;                      ///< where the recorded run stopped [ns]
};

/// The command of `list` in force at t_ns: the last with t_ns <= t_ns; nullptr before the first.
template <class Command>
const Command* commandInForce(const std::vector<Command>& list, std::int64_t t_ns) {
  const auto after = std::upper_bound(list.begin(), list.end(), t_ns,
                                      [](std::int64_t t, const Command& c) { return t < c.t_ns; });
  return after == list.begin() ? nullptr : &*(after - 1);
}

}  // namespace climbsim::controller
