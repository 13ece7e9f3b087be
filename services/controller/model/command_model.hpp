#pragma once
/// @file
/// What `climbsim-controller` commands at a step, by the scenario's controller type, as a model
/// of the contract (docs/design.md#the-model-contract): Params, State, Inputs, Outputs and
/// `Outputs step(State&, const Inputs&, t_ns, dt_ns) const`. No DDS: node/ translates the thermo
/// samples into Inputs and the Outputs into ValveCommand, EngineCommand and DriveCommand.
///
/// - none: every valve closed; fixed: the scenario's openings; reference: the adhesion
///   controller on the held measurement, with the valves where the robot has a reservoir
///   (adhesion_controller.hpp), with the engines' speed where it has none (engine_controller.hpp);
///   external: no valve command (another client commands the valves, and the engines of a robot
///   without a reservoir); recorded: the valve and engine commands of a recorded run in force at
///   t_ns, with its set-point (recorded_commands.hpp; before its first valve command the valves
///   are closed, before its first engine command the engines run at full speed).
/// - The engines are on at full speed unless the engine law sets their speed; the drive follows
///   the scenario's schedule at t_ns.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "adhesion_controller.hpp"
#include "engine_controller.hpp"
#include "recorded_commands.hpp"
#include "climbsim/robot/robot_description.hpp"
#include "climbsim/robot/robot_geometry.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/model_contract.hpp"

namespace climbsim::controller {

/// What the controller service needs of the scenario and the robot.
struct ControllerParams {
  Scenario::ControllerKind kind = Scenario::ControllerKind::kReference;
  int chamber_count = 7;                             ///< N chambers
  bool has_reservoir = true;                         ///< a reservoir, and one valve per chamber on it
  std::vector<double> fixed_valves;                  ///< kFixed: N openings 0..1
  std::vector<Scenario::DriveCommand> drive;         ///< the schedule (first entry at t = 0)
  int engine_count = 3;                              ///< the robot's engines
  AdhesionControllerParams reference;                ///< kReference with a reservoir: params incl. set-point, balance
  EngineControllerParams engine_reference;           ///< kReference without a reservoir: the engine law's
  RecordedCommands recorded;                         ///< kRecorded: what it plays back
};

/// The scenario's controller section and drive schedule with the robot's controller params.
ControllerParams controllerParams(const Scenario& scenario, const RobotDescription& robot,
                                  const RobotGeometry& geometry);

/// The held measurement (the last valid thermo values; initially ambient pressure, F = 0) and
/// the reference controller's state (empty for the other types; the engine law's without a reservoir).
struct ControllerState {
  AdhesionMeasurement measured;
  std::optional<AdhesionControllerState> reference;
  std::optional<EngineControllerState> engine_reference;
};

/// The thermo values of this step that passed the node's checks (finite), if any.
struct ControllerInputs {
  std::optional<std::vector<double>> pressure_pa;    ///< chambers 1..N, then the reservoir if any [Pa]
  std::optional<double> downforce_n;                 ///< F [N] (with p_RobotPF_m)
  std::array<double, 2> p_RobotPF_m{};               ///< P_F (x, y) in the robot frame [m]
};

/// The commands of one step.
struct ControllerOutputs {
  bool commands_valves = true;                      ///< false for type external
  std::vector<double> valve_opening;                ///< N openings 0..1 (closed for none)
  double downforce_setpoint_n = 0.0;                ///< the reference controller's F* in force [N]; 0: none
  bool commands_engines = true;                     ///< false for type external on a robot without a reservoir
  std::vector<double> engine_speed;                 ///< one speed 0..1 per engine (1: full speed), all on
  Scenario::DriveCommand drive;                     ///< body velocity command at t_ns
};

class ControllerModel {
 public:
  /// The model contract's types (climbsim/model_contract.hpp).
  using Params = ControllerParams;
  using State = ControllerState;
  using Inputs = ControllerInputs;
  using Outputs = ControllerOutputs;

  /// Validates the reference controller's params (ConfigError) when the type is reference.
  explicit ControllerModel(ControllerParams params);

  ControllerState initialState() const;

  /// The commands for the step starting at t_ns [ns] (period dt_ns [ns]); `in`'s values replace
  /// the held ones first.
  ControllerOutputs step(ControllerState& state, const ControllerInputs& in, std::int64_t t_ns,
                         std::int64_t dt_ns) const;

  bool commandsValves() const { return params_.kind != Scenario::ControllerKind::kExternal; }
  /// The engines are the external client's where they hold the downforce (no reservoir).
  bool commandsEngines() const { return commandsValves() || params_.has_reservoir; }

 private:
  ControllerParams params_;
  std::optional<AdhesionController> reference_;
  std::optional<EngineController> engine_reference_;
};

static_assert(is_model_v<ControllerModel>, "ControllerModel keeps the model contract");

}  // namespace climbsim::controller
