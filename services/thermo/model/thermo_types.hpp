#pragma once
/// @file
/// State, inputs and outputs of the airflow model (docs/design.md#airflow-and-downforce,
/// docs/design.md#the-model-contract).

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "ode_system.hpp"
#include "thermo_params.hpp"

namespace climbsim::thermo {

/// A valve command waiting out its pure delay.
struct PendingValveCommand {
  std::int64_t activation_t_ns = 0;  ///< when it becomes the valve's target [ns, clock time]
  int chamber = 0;                   ///< 0..N-1 (chamber 1..N)
  double opening = 0.0;              ///< commanded opening, 0..1
};

/// Everything that evolves. Make it with ThermoModel::initialState(); step() advances it.
struct ThermoState {
  std::int64_t t_ns = 0;                          ///< clock time the state refers to [ns]
  std::vector<double> pressure_pa;                ///< chambers 1..N, then the reservoir if any [Pa]
  std::vector<double> engine_speed;               ///< per engine, 0..1 (1 = full speed)
  std::vector<double> engine_speed_command;       ///< per engine, 0..1: what the lag follows
  std::vector<double> valve_opening;  ///< per valve (ThermoParams::valveCount()), 0..1
  std::vector<double> valve_target;   ///< per valve: the delayed command now in force, 0..1
  /// Commands not yet in force, in order of activation time (ties: order of arrival).
  std::vector<PendingValveCommand> pending_valve_commands;
  double ambient_inflow_kg = 0.0;   ///< cumulative mass that entered from the ambient [kg]
  double engine_outflow_kg = 0.0;   ///< cumulative mass the engines removed [kg]
  double next_step_s = 1e-4;        ///< the integrator's step proposal, carried between calls [s]
  double stiffness_hint_per_s = 0.0;  ///< the integrator's last stiffness bound (RhsCarry) [1/s]
  /// Per ThermoParams::faults: has taken effect (a stuck valve has been retargeted once).
  std::vector<char> fault_in_force;
};

/// Command of one suction engine.
struct EngineCommand {
  bool on = false;
  double speed = 1.0;  ///< 0..1; the lag follows `on ? speed : 0`
};

/// Inputs of one step, held constant over it (zero-order hold).
struct ThermoInputs {
  std::vector<double> leak_area_m2;   ///< per sealing segment, finite and >= 0
  /// Opening per valve, i.e. per chamber 1..N with a reservoir (empty without), in [0, 1].
  std::vector<double> valve_command;
  std::vector<EngineCommand> engines; ///< one per engine
};

/// A sample the model refuses (wrong sizes, NaN, out of range). The node logs, counts and
/// drops it and holds the last valid inputs.
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// "" when `inputs` fit `params`, else a one-line reason naming the field and value or the
/// sizes, e.g. "thermo input: valve_command[3] = 1.5 (must be in [0, 1])",
/// "thermo input: valve_command has 7 entries, the robot has 4 valves".
std::string validateInputs(const ThermoParams& params, const ThermoInputs& inputs);

/// What the model reports at the end of a step (t_ns + dt_ns).
struct ThermoOutputs {
  std::int64_t t_ns = 0;                          ///< end of the step [ns]
  std::vector<double> pressure_pa;  ///< chambers 1..N, then the reservoir if any [Pa]
  /// Mass flow through each sealing segment at t_ns, positive from volume_a to volume_b [kg/s].
  std::vector<double> segment_mass_flow_kgps;
  /// Mass flow through each valve at t_ns, positive from the chamber to the reservoir [kg/s]
  /// (none without a reservoir).
  std::vector<double> valve_mass_flow_kgps;
  std::vector<double> engine_mass_flow_kgps;  ///< per engine, out of the volume it pumps [kg/s]
  std::vector<double> valve_opening;          ///< per valve, 0..1 (none without a reservoir)
  std::vector<double> engine_speed;           ///< 0..1
  /// F = sum_i (p_o - p_i) A_i over chambers 1..N [N]; > 0 pulls the robot to the wall.
  double downforce_n = 0.0;
  /// M = sum_i P_i (p_o - p_i) A_i, the first moment of the suction about the robot
  /// origin [N m] (x, y); well defined even where P_F is not.
  std::array<double, 2> suction_moment_nm{};
  /// P_F = M / F in the robot frame [m] when F > 0. When F <= 0 there is no pull to
  /// place; P_F is then the suction-area centroid sum_i P_i A_i / sum_i A_i (where a
  /// uniform pressure would act), so consumers never see inf/NaN; use suction_moment_nm
  /// for the exact moment.
  std::array<double, 2> p_RobotPF_m{};
  double ambient_inflow_kg = 0.0;   ///< cumulative, as in ThermoState
  double engine_outflow_kg = 0.0;   ///< cumulative, as in ThermoState
  /// sum_i p_i V_i / (kappa R T) over chambers and the reservoir if any [kg]: the air mass the ODE
  /// conserves (with kappa in dp/dt the conserved quantity carries the same 1/kappa),
  /// so air_mass_kg - ambient_inflow_kg + engine_outflow_kg is constant in time.
  double air_mass_kg = 0.0;
  IntegratorStats integrator;       ///< work of this step only
  /// Indices into ThermoParams::faults of the faults that took effect at this step's start.
  std::vector<std::size_t> faults_taking_effect;
};

}  // namespace climbsim::thermo
