#include "controller_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

namespace climbsim::controller {
namespace {

bool finite(const climbsim::ChamberState& s) {
  for (double p : s.pressure_pa()) {
    if (!std::isfinite(p)) return false;
  }
  return true;
}

bool finite(const climbsim::AdhesionForce& f) {
  return std::isfinite(f.downforce_n()) && std::isfinite(f.pf_x_m()) && std::isfinite(f.pf_y_m());
}

}  // namespace

ControllerNode::ControllerNode(ControllerParams config)
    : expected_pressures_(static_cast<std::size_t>(config.chamber_count + (config.has_reservoir ? 1 : 0))),
      model_(std::move(config)),
      state_(model_.initialState()) {}

ControllerCommands ControllerNode::step(std::int64_t t_ns, std::int64_t dt_ns,
                                        const std::vector<climbsim::ChamberState>& states,
                                        const std::vector<climbsim::AdhesionForce>& forces) {
  ControllerInputs in;
  for (const auto& s : states) {
    if (s.pressure_pa().size() != expected_pressures_) {
      ++dropped_;
      spdlog::warn("controller: dropped thermo/ChamberState from {} at step {}: {} pressures, the robot has {} volumes",
                   s.source().c_str(), s.step(), s.pressure_pa().size(), expected_pressures_);
      continue;
    }
    if (!finite(s)) {
      ++dropped_;
      spdlog::warn("controller: dropped ChamberState from {} at step {}: a pressure is not finite", s.source().c_str(),
                   s.step());
      continue;
    }
    in.pressure_pa.emplace(s.pressure_pa().begin(), s.pressure_pa().end());
  }
  for (const auto& f : forces) {
    if (!finite(f)) {
      ++dropped_;
      spdlog::warn("controller: dropped AdhesionForce from {} at step {}: a value is not finite", f.source().c_str(),
                   f.step());
      continue;
    }
    in.downforce_n = f.downforce_n();
    in.p_RobotPF_m = {f.pf_x_m(), f.pf_y_m()};
  }
  const ControllerOutputs commands = model_.step(state_, in, t_ns, dt_ns);

  ControllerCommands out;
  if (commands.commands_valves) {
    climbsim::ValveCommand valves;
    valves.opening().assign(commands.valve_opening.begin(), commands.valve_opening.end());
    valves.downforce_setpoint_n(commands.downforce_setpoint_n);
    out.valves = valves;
  }
  if (commands.commands_engines) {
    out.engines.emplace();
    for (double speed : commands.engine_speed) {
      climbsim::EngineSetting engine;
      engine.on(true);
      engine.speed(speed);
      out.engines->engines().push_back(engine);
    }
  }
  out.drive.vx_mps(commands.drive.vx_mps);
  out.drive.vy_mps(commands.drive.vy_mps);
  out.drive.wz_radps(commands.drive.wz_radps);
  return out;
}

}  // namespace climbsim::controller
