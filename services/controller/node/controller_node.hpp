#pragma once
/// @file
/// The controller service's translation between DDS samples and its command model
/// (command_model.hpp): thermo's samples (checked finite) in, the commands' IDL out.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "command_model.hpp"
#include "climbsim/scenario.hpp"
#include "robot.h"
#include "thermo.h"

namespace climbsim::controller {

/// Commands of one step. `valves` is empty when this process does not command the valves
/// (type external: another client does), `engines` when it does not command the engines (type
/// external on a robot without a reservoir); the valves' downforce_setpoint_n is the reference
/// controller's F* in force (0 for the types none and fixed, which have no set-point).
struct ControllerCommands {
  std::optional<climbsim::ValveCommand> valves;
  std::optional<climbsim::EngineCommand> engines;
  climbsim::DriveCommand drive;
};

class ControllerNode {
 public:
  using Model = ControllerModel;  ///< the model it steps (model_contract.hpp)

  explicit ControllerNode(ControllerParams config);

  /// The commands for the step starting at t_ns (period dt_ns), from the latest thermo samples
  /// (one per producer; the last valid pair is held, initially ambient pressure and F = 0).
  /// A sample with a non-finite value is logged, counted and dropped.
  ControllerCommands step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::ChamberState>& states,
                          const std::vector<climbsim::AdhesionForce>& forces);

  bool commandsValves() const { return model_.commandsValves(); }
  bool commandsEngines() const { return model_.commandsEngines(); }
  std::uint64_t droppedSamples() const { return dropped_; }
  const AdhesionMeasurement& heldMeasurement() const { return state_.measured; }
  /// The reference controller's state (empty for the other types and without a reservoir).
  const std::optional<AdhesionControllerState>& referenceState() const { return state_.reference; }
  /// The engine law's state (the reference controller without a reservoir; else empty).
  const std::optional<EngineControllerState>& engineReferenceState() const { return state_.engine_reference; }

 private:
  std::size_t expected_pressures_;  ///< N chambers, and the reservoir if any
  ControllerModel model_;
  ControllerState state_;
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim::controller
