#pragma once
/// @file
/// The thermo service without DDS: the leakage merger and the input holding of
/// `climbsim-thermo` (docs/design.md#airflow-and-downforce, docs/design.md#sealing-and-leakage).
/// main.cpp only moves samples in and out.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "climbsim/leakage_merger.hpp"
#include "sealing.h"
#include "thermo.h"
#include "thermo_model.hpp"

namespace climbsim::thermo {

/// The merger of Leakage parts (several sealing shards): common/, shared with the recorder.
using climbsim::LeakageMerger;

/// Which inputs `climbsim-thermo` reads; an absent one keeps its default for the whole run.
struct ThermoNodeInputs {
  bool leakage = true;  ///< "sealing/Leakage"; default: basic leakage l_i * L_basic
  bool valves = true;   ///< "controller/ValveCommand"; default: all closed
  bool engines = true;  ///< "controller/EngineCommand"; default: all off (speed 1)
};

/// Parses "leakage,valves,engines" (any subset, "none" for none); ConfigError naming --inputs.
ThermoNodeInputs parseThermoNodeInputs(const std::string& list);

/// Input holding and stepping of the thermo service. Bad ValveCommand / EngineCommand
/// samples (validateInputs gives the reason) are logged, counted and dropped; the last
/// valid command is held. Several producers of a command topic: applied in the order given
/// (producer name), so the last valid one wins.
///
/// Plant faults (ThermoParams::faults, plantFaultsFromScenario) act in the model
/// (ThermoModel::step): the node logs each one when it takes effect.
class ThermoNode {
 public:
  using Model = ThermoModel;  ///< the model it steps (model_contract.hpp)

  /// `segment_names` and `basic_leak_area_m2` in the order of params.segments; params.faults
  /// are the plant faults (ThermoModel validates them: ConfigError).
  ThermoNode(ThermoParams params, std::vector<std::string> segment_names, std::vector<double> basic_leak_area_m2);

  /// One due step [t_ns, t_ns + dt_ns): merges the samples into the held inputs, steps the
  /// model (the state starts at ambient at the first call's t_ns) and returns its outputs at
  /// t_ns + dt_ns. dt_ns is the participant's period in ns (clock dt * period steps).
  ThermoOutputs step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::Leakage>& leakage,
                     const std::vector<climbsim::ValveCommand>& valves,
                     const std::vector<climbsim::EngineCommand>& engines);

  /// The outputs before the first step (the state starts at ambient at t_ns, the held
  /// inputs are the defaults: basic leakage): the recorder's initial state (row 0).
  ThermoOutputs initialOutputs(std::int64_t t_ns = 0) const {
    return model_.outputsOf(state_ ? *state_ : model_.initialState(t_ns), inputs_.leak_area_m2);
  }

  /// The downforce set-point of the last valid ValveCommand [N] (0: none stated, or no command
  /// yet): thermo passes it on in AdhesionForce.downforce_setpoint_n, so that the trace and the
  /// plots show the set-point of whichever controller commands the valves. A command whose
  /// set-point is not finite or outside [0, 1e6] N is dropped like one with a bad opening.
  double downforceSetpoint() const { return setpoint_n_; }

  /// The commands as received (faults not applied).
  const ThermoInputs& heldInputs() const { return inputs_; }
  const LeakageMerger& leakage() const { return merger_; }
  std::uint64_t droppedValveCommands() const { return dropped_valves_; }
  std::uint64_t droppedEngineCommands() const { return dropped_engines_; }
  const ThermoModel& model() const { return model_; }

 private:
  /// Applies a command sample to a copy of the held inputs; keeps the copy (true) if the
  /// model accepts it, else logs, counts in `dropped` and holds the last valid (false).
  template <class Sample, class Apply>
  bool applyCommand(const Sample& sample, const char* topic, std::uint64_t& dropped, const Apply& apply);

  /// Logs a fault that takes effect at t_ns (ThermoOutputs::faults_taking_effect).
  static void logFault(const PlantFault& fault, std::int64_t t_ns);

  ThermoModel model_;
  LeakageMerger merger_;
  ThermoInputs inputs_;
  std::optional<ThermoState> state_;
  double setpoint_n_ = 0.0;
  std::uint64_t dropped_valves_ = 0;
  std::uint64_t dropped_engines_ = 0;
};

}  // namespace climbsim::thermo
