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

ControllerNodeConfig controllerNodeConfig(const Scenario& scenario, const RobotDescription& robot,
                                          const RobotGeometry& geometry) {
  ControllerNodeConfig c;
  c.kind = scenario.controller.kind;
  c.fixed_valves = scenario.controller.valves;
  c.drive = scenario.drive;
  c.engine_count = robot.engines.count;
  c.reference = adhesionControllerParamsFromRobot(robot, geometry);
  if (scenario.controller.downforce_n > 0.0) c.reference.desired_downforce_n = scenario.controller.downforce_n;
  c.reference.balance = scenario.controller.balance;
  return c;
}

ControllerNode::ControllerNode(ControllerNodeConfig config) : config_(std::move(config)) {
  measured_.pressure_pa.fill(config_.reference.ambient_pressure_pa);
  if (config_.kind == Scenario::ControllerKind::kReference) {
    reference_.emplace(config_.reference);
    reference_state_ = reference_->initialState();
  }
}

ControllerCommands ControllerNode::step(std::int64_t t_ns, std::int64_t dt_ns,
                                        const std::vector<climbsim::ChamberState>& states,
                                        const std::vector<climbsim::AdhesionForce>& forces) {
  for (const auto& s : states) {
    if (!finite(s)) {
      ++dropped_;
      spdlog::warn("controller: dropped ChamberState from {} at step {}: a pressure is not finite", s.source().c_str(),
                   s.step());
      continue;
    }
    std::copy(s.pressure_pa().begin(), s.pressure_pa().end(), measured_.pressure_pa.begin());
  }
  for (const auto& f : forces) {
    if (!finite(f)) {
      ++dropped_;
      spdlog::warn("controller: dropped AdhesionForce from {} at step {}: a value is not finite", f.source().c_str(),
                   f.step());
      continue;
    }
    measured_.downforce_n = f.downforce_n();
    measured_.p_RobotPF_m = {f.pf_x_m(), f.pf_y_m()};
  }

  ControllerCommands out;
  std::array<double, kValveCount> openings{};
  switch (config_.kind) {
    case Scenario::ControllerKind::kNone: break;  // valves closed
    case Scenario::ControllerKind::kFixed: openings = config_.fixed_valves; break;
    case Scenario::ControllerKind::kReference:
      openings = reference_->step(*reference_state_, measured_, t_ns, dt_ns).valve_opening;
      break;
    case Scenario::ControllerKind::kExternal: break;
  }
  if (commandsValves()) {
    climbsim::ValveCommand valves;
    std::copy(openings.begin(), openings.end(), valves.opening().begin());
    // The set-point in force, so that the trace and the plots show this controller's own
    // (fixed and none state none: 0).
    valves.downforce_setpoint_n(reference_state_ ? reference_state_->desired_downforce_n : 0.0);
    out.valves = valves;
  }
  for (int i = 0; i < config_.engine_count; ++i) {
    climbsim::EngineSetting engine;
    engine.on(true);
    engine.speed(1.0);
    out.engines.engines().push_back(engine);
  }
  const Scenario::DriveCommand cmd = driveCommandAt(config_.drive, t_ns);
  out.drive.vx_mps(cmd.vx_mps);
  out.drive.vy_mps(cmd.vy_mps);
  out.drive.wz_radps(cmd.wz_radps);
  return out;
}

}  // namespace climbsim::controller
