#include "downforce_log.hpp"

#include <spdlog/fmt/fmt.h>

#include <stdexcept>
#include <utility>

namespace climbsim::downforce_log {

DownforceLog::DownforceLog(Params params) : params_(std::move(params)) {
  if (params_.period_ns <= 0) {
    throw std::invalid_argument("downforce log: the period must be > 0 ns (got " +
                                std::to_string(params_.period_ns) + ")");
  }
}

DownforceLog::Outputs DownforceLog::step(State& state, const Inputs& inputs, std::int64_t t_ns,
                                         std::int64_t dt_ns) const {
  Outputs out;
  const std::int64_t holds_ns = t_ns + dt_ns;
  out.t_s = static_cast<double>(holds_ns) / 1e9;
  if (holds_ns < state.next_due_ns) return out;
  out.due = true;
  out.line = formatLine(out.t_s, inputs);
  state.next_due_ns = (holds_ns / params_.period_ns + 1) * params_.period_ns;
  return out;
}

std::string formatLine(double t_s, const DownforceLogInputs& inputs) {
  const std::string setpoint =
      inputs.setpoint_n > 0.0 ? fmt::format("set-point {:.0f} N", inputs.setpoint_n) : std::string("no set-point");
  return fmt::format("t = {:.3f} s: F = {:.1f} N ({})", t_s, inputs.downforce_n, setpoint);
}

}  // namespace climbsim::downforce_log
