#pragma once
/// @file
/// The controller's validated configuration as JSON, for the controller clients in other
/// languages (`climbsim-controller --scenario FILE --print-config`): the Python port reads
/// this instead of parsing the scenario and robot files itself, so that the scenario and
/// robot files have one validation (loadScenario, loadRobotDescription: their
/// `file:line: key = value: why` messages) and the Python port gets the very doubles the C++
/// controller uses.

#include <nlohmann/json.hpp>

#include "climbsim/scenario.hpp"
#include "node/controller_node.hpp"

namespace climbsim::controller {

/// {"scenario", "source", "controller" (none|fixed|reference|external), "fixed_valves" [N],
///  "engine_count", "chamber_count", "has_reservoir", "drive" [{t_s, vx_mps, vy_mps, wz_radps}], "reference" {the
///  fields of AdhesionControllerParams a scenario and robot set: ambient_pressure_pa,
///  chamber_area_m2 [m^2], p_RobotChamber_m [[x, y] m], desired_downforce_n (scenario's set-point
///  applied), balance, max_suction_pa, valve_full_stroke_s, valve_command_delay_s,
///  fan_max_suction_pa}, "engine_reference" {every field of EngineControllerParams; filled for
///  the reference controller on a robot without a reservoir}}.
nlohmann::json clientConfigJson(const Scenario& scenario, const ControllerParams& config);

}  // namespace climbsim::controller
