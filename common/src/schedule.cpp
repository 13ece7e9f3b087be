#include "climbsim/schedule.hpp"

#include "climbsim/errors.hpp"

namespace climbsim {

void Schedule::validate(const std::string& what) const {
  if (period_steps == 0) {
    throw ConfigError(what + ": period_steps = 0; it must be >= 1");
  }
  if (offset_steps >= period_steps) {
    throw ConfigError(what + ": offset_steps = " + std::to_string(offset_steps) +
                      "; it must be < period_steps = " + std::to_string(period_steps));
  }
}

bool Schedule::isDue(std::uint64_t step) const {
  return step >= offset_steps && (step - offset_steps) % period_steps == 0;
}

std::optional<std::uint64_t> Schedule::lastDueBefore(std::uint64_t step) const {
  if (step <= offset_steps) {
    return std::nullopt;
  }
  const std::uint64_t since_first = step - 1 - offset_steps;
  return offset_steps + since_first - since_first % period_steps;
}

std::uint64_t Schedule::nextDueFrom(std::uint64_t step) const {
  if (step <= offset_steps) {
    return offset_steps;
  }
  const std::uint64_t since_first = step - offset_steps;
  const std::uint64_t rem = since_first % period_steps;
  return rem == 0 ? step : step + (period_steps - rem);
}

std::uint64_t Schedule::dueCount(std::uint64_t end_step) const {
  if (end_step <= offset_steps) {
    return 0;
  }
  return (end_step - 1 - offset_steps) / period_steps + 1;
}

}  // namespace climbsim
