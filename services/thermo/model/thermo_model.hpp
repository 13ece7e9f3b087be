#pragma once
/// @file
/// The thermo model (docs/design.md#airflow-and-downforce): chambers 1..N, a reservoir with one
/// valve per chamber or none, ambient, sealing leaks, suction engines, downforce. Pure C++: no DDS, no wall clock; time comes
/// in as an argument from the simulation clock.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "airflow_system.hpp"
#include "thermo_params.hpp"
#include "thermo_types.hpp"
#include "climbsim/model_contract.hpp"

namespace climbsim::thermo {

/// Steps the airflow ODE over one exchange period, substepping adaptively inside it.
/// Deterministic: the same params, state and inputs give bit-identical results.
class ThermoModel {
 public:
  /// The model contract's types (climbsim/model_contract.hpp).
  using Params = ThermoParams;
  using State = ThermoState;
  using Inputs = ThermoInputs;
  using Outputs = ThermoOutputs;

  /// Validates params (climbsim::ConfigError naming the parameter and value).
  explicit ThermoModel(ThermoParams params);

  const ThermoParams& params() const { return params_; }

  /// Every volume at ambient pressure, engines stopped, valves closed, no pending commands,
  /// counters zero, at clock time t_ns.
  ThermoState initialState(std::int64_t t_ns = 0) const;

  /// The outputs of `state` as it stands (openings and engine speeds held, nothing moving)
  /// with the leak areas `leak_area_m2` (one per segment): pressures, openings, engine
  /// speeds, the flows at that instant, F and P_F, the air mass. For the state before the
  /// first step (the trace's row 0); integrator stats are zero. Throws InvalidInputError for
  /// leak areas validateInputs refuses.
  ThermoOutputs outputsOf(const ThermoState& state, const std::vector<double>& leak_area_m2) const;

  /// Advances state from t_ns (must equal state.t_ns) to t_ns + dt_ns (dt_ns > 0) with
  /// inputs held over the step:
  ///  - the plant faults of params.faults in force at t_ns (PlantFault) override the inputs'
  ///    valve and engine commands; one that takes effect now retargets its valve in the state
  ///    and is listed in the outputs' faults_taking_effect;
  ///  - valve commands are queued to take effect at t_ns + delay (valve_actuator.hpp);
  ///    openings then move at 1 / full_stroke_s towards the target in force;
  ///  - engine speeds follow `on ? speed : 0` from t_ns with their first-order lag;
  ///  - the pressures follow AirflowSystem (airflow_system.hpp) with params.integrator,
  ///    in pieces that end at every valve activation (a target jump) and every landing of
  ///    a valve on its target, so that no integrator step spans a corner of an opening's
  ///    trajectory; the step-size proposal and the stiffness hint are carried in
  ///    state.next_step_s and state.stiffness_hint_per_s from one call to the next, and
  ///    f from one piece to the next (RhsCarry).
  /// Returns the outputs at t_ns + dt_ns. Throws InvalidInputError (validateInputs) for a
  /// bad sample, std::logic_error for a time that does not match the state or dt_ns <= 0,
  /// std::runtime_error if the integrator fails; in every case state is left unchanged.
  ThermoOutputs step(ThermoState& state, const ThermoInputs& inputs, std::int64_t t_ns, std::int64_t dt_ns) const;

 private:
  /// Writes the outputs of `state` with its connections' flows `flows` (moved from) into `out`
  /// (every field but the integrator's statistics): the pressures, flows and openings as they
  /// are, the downforce and P_F from the pressures (computeDownforce), and the air mass
  /// sum_i p_i V_i / (kappa R T) over the chambers and the reservoir if any [kg].
  void fillOutputs(const ThermoState& state, ConnectionFlows& flows, ThermoOutputs& out) const;
  /// Stuck valves in force at t_ns: their command becomes the stuck opening; one that takes
  /// effect now also sets its valve's target and drops the commands pending for it.
  void applyValveFaults(ThermoState& s, std::vector<double>& valve_command, std::int64_t t_ns,
                        std::vector<std::size_t>& taking_effect) const;
  /// Failed engines in force at t_ns: their speed command becomes 0.
  void applyEngineFaults(ThermoState& s, std::int64_t t_ns, std::vector<std::size_t>& taking_effect) const;
  /// The state's vectors are sized for params_ (pressures, valves, engines, faults).
  bool fitsParams(const ThermoState& state) const;
  /// "a state with 8 pressures, 7 valves, 3 engines, 0 faults", for error messages.
  static std::string describeSizes(const ThermoState& state);
  /// "8 pressures, 7 valves, 3 engines, 0 faults" of params_.
  std::string describeParamsSizes() const;
  /// y = (pressures, ambient inflow, engine outflow) of `state` (fitsParams).
  OdeVector odeState(const ThermoState& state) const;

  /// params_ after validate() (ConfigError naming the parameter and value).
  static const ThermoParams& validated(const ThermoParams& params);

  ThermoParams params_;
  AirflowLayout layout_;  ///< what every exchange period's AirflowSystem derives from params_
  std::int64_t valve_delay_ns_ = 0;
};

static_assert(is_model_v<ThermoModel>, "ThermoModel keeps the model contract");

}  // namespace climbsim::thermo
