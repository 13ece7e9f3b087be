#include "command_model.hpp"

#include <utility>

namespace climbsim::controller {

ControllerParams controllerParams(const Scenario& scenario, const RobotDescription& robot,
                                  const RobotGeometry& geometry) {
  ControllerParams c;
  c.kind = scenario.controller.kind;
  c.chamber_count = geometry.chamberCount();
  c.has_reservoir = geometry.has_reservoir;
  c.fixed_valves = scenario.controller.valves;
  c.drive = scenario.drive;
  c.engine_count = robot.engines.count;
  c.reference.ambient_pressure_pa = robot.gas.ambient_pressure_pa;
  if (c.kind != Scenario::ControllerKind::kReference) return c;  // only the reference controller needs its law
  if (!c.has_reservoir) {
    c.engine_reference = engineControllerParamsFromRobot(robot, geometry);
    if (scenario.controller.downforce_n > 0.0) c.engine_reference.desired_downforce_n = scenario.controller.downforce_n;
    c.engine_reference.balance = scenario.controller.balance;
    return c;
  }
  c.reference = adhesionControllerParamsFromRobot(robot, geometry);
  if (scenario.controller.downforce_n > 0.0) c.reference.desired_downforce_n = scenario.controller.downforce_n;
  c.reference.balance = scenario.controller.balance;
  return c;
}

ControllerModel::ControllerModel(ControllerParams params) : params_(std::move(params)) {
  if (params_.kind != Scenario::ControllerKind::kReference) return;
  if (params_.has_reservoir) {
    reference_.emplace(params_.reference);
  } else {
    engine_reference_.emplace(params_.engine_reference);
  }
}

ControllerState ControllerModel::initialState() const {
  ControllerState state;
  state.measured.pressure_pa.assign(static_cast<std::size_t>(params_.chamber_count + (params_.has_reservoir ? 1 : 0)),
                                    params_.reference.ambient_pressure_pa);
  if (reference_) state.reference = reference_->initialState();
  if (engine_reference_) state.engine_reference = engine_reference_->initialState();
  return state;
}

ControllerOutputs ControllerModel::step(ControllerState& state, const ControllerInputs& in, std::int64_t t_ns,
                                        std::int64_t dt_ns) const {
  if (in.pressure_pa) state.measured.pressure_pa = *in.pressure_pa;
  if (in.downforce_n) {
    state.measured.downforce_n = *in.downforce_n;
    state.measured.p_RobotPF_m = in.p_RobotPF_m;
  }
  ControllerOutputs out;
  out.commands_valves = commandsValves();
  // One opening per valve: none without a reservoir (the command still carries the set-point).
  out.valve_opening.assign(params_.has_reservoir ? static_cast<std::size_t>(params_.chamber_count) : 0, 0.0);
  switch (params_.kind) {
    case Scenario::ControllerKind::kNone: break;  // valves closed
    case Scenario::ControllerKind::kFixed: out.valve_opening = params_.fixed_valves; break;
    case Scenario::ControllerKind::kReference:
      if (reference_) out.valve_opening = reference_->step(*state.reference, state.measured, t_ns, dt_ns).valve_opening;
      break;
    case Scenario::ControllerKind::kExternal: break;
    case Scenario::ControllerKind::kRecorded: break;  // below
  }
  // The set-point in force, so that the trace and the plots show this controller's own
  // (fixed and none state none: 0).
  out.downforce_setpoint_n = state.reference ? state.reference->desired_downforce_n : 0.0;
  out.commands_engines = commandsEngines();
  if (engine_reference_) {
    out.engine_speed = engine_reference_->step(*state.engine_reference, state.measured, t_ns, dt_ns).engine_speed;
    out.downforce_setpoint_n = state.engine_reference->desired_downforce_n;
  } else if (out.commands_engines) {
    out.engine_speed.assign(static_cast<std::size_t>(params_.engine_count), 1.0);
  }
  if (params_.kind == Scenario::ControllerKind::kRecorded) {
    if (const auto* valves = commandInForce(params_.recorded.valves, t_ns)) {
      out.valve_opening = valves->opening;
      out.downforce_setpoint_n = valves->downforce_setpoint_n;
    }
    if (const auto* engines = commandInForce(params_.recorded.engines, t_ns)) out.engine_speed = engines->speed;
  }
  out.drive = driveCommandAt(params_.drive, t_ns);
  return out;
}

}  // namespace climbsim::controller
