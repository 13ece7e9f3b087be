#include "solo_clock_messages.hpp"

namespace climbsim::solo {

climbsim::RunStart soloRunStart(std::int64_t dt_ns, std::uint64_t end_step,
                                const std::vector<std::pair<std::string, Schedule>>& roster) {
  climbsim::RunStart start;
  start.run_id(0);
  start.dt_ns(dt_ns);
  start.end_step(end_step);
  start.window_steps(0);
  for (const auto& [name, schedule] : roster) {
    climbsim::RosterEntry entry;
    entry.participant(name);
    entry.period_steps(schedule.period_steps);
    entry.offset_steps(schedule.offset_steps);
    start.roster().push_back(entry);
  }
  return start;
}

climbsim::Stop soloStop(std::uint64_t steps, std::int64_t dt_ns, const std::string& outcome,
                        const std::string& culprit, const std::string& reason) {
  climbsim::Stop stop;
  stop.run_id(0);
  stop.last_step(steps > 0 ? steps - 1 : 0);
  stop.t_ns(static_cast<std::int64_t>(steps) * dt_ns);
  stop.kind(outcome == "completed" ? STOP_COMPLETED
            : outcome == "stopped" ? STOP_REQUESTED
            : outcome == "fell"    ? STOP_FELL
                                   : STOP_FAILED);
  stop.culprit(culprit);
  stop.reason(reason.substr(0, 512));
  return stop;
}

}  // namespace climbsim::solo
