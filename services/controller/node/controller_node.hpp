#pragma once
/// @file
/// The controller service without DDS entities: which commands `climbsim-controller` sends at a
/// step, from the scenario's controller type, its drive schedule and the thermo measurements.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "adhesion_controller.hpp"
#include "climbsim/scenario.hpp"
#include "robot.h"
#include "thermo.h"

namespace climbsim::controller {

/// What the node needs of the scenario and the robot.
struct ControllerNodeConfig {
  Scenario::ControllerKind kind = Scenario::ControllerKind::kReference;
  std::array<double, kValveCount> fixed_valves{};    ///< kFixed: openings 0..1
  std::vector<Scenario::DriveCommand> drive;         ///< the schedule (first entry at t = 0)
  int engine_count = 3;                              ///< engines commanded on at full speed
  AdhesionControllerParams reference;                ///< kReference: params incl. set-point, balance
};

/// The scenario's controller section and drive schedule with the robot's controller params.
ControllerNodeConfig controllerNodeConfig(const Scenario& scenario, const RobotDescription& robot,
                                          const RobotGeometry& geometry);

/// Commands of one step. `valves` is empty when this process does not command the valves
/// (type external: another client does); its downforce_setpoint_n is the reference
/// controller's F* in force (0 for the types none and fixed, which have no set-point).
struct ControllerCommands {
  std::optional<climbsim::ValveCommand> valves;
  climbsim::EngineCommand engines;
  climbsim::DriveCommand drive;
};

class ControllerNode {
 public:
  explicit ControllerNode(ControllerNodeConfig config);

  /// The commands for the step starting at t_ns (period dt_ns), from the latest thermo samples
  /// (one per producer; the last valid pair is held, initially ambient pressure and F = 0).
  /// A sample with a non-finite value is logged, counted and dropped.
  ControllerCommands step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::ChamberState>& states,
                          const std::vector<climbsim::AdhesionForce>& forces);

  bool commandsValves() const { return config_.kind != Scenario::ControllerKind::kExternal; }
  std::uint64_t droppedSamples() const { return dropped_; }
  const AdhesionMeasurement& heldMeasurement() const { return measured_; }
  /// The reference controller's state (empty for the other types).
  const std::optional<AdhesionControllerState>& referenceState() const { return reference_state_; }

 private:
  ControllerNodeConfig config_;
  std::optional<AdhesionController> reference_;
  std::optional<AdhesionControllerState> reference_state_;  ///< the reference controller's state
  AdhesionMeasurement measured_;
  std::uint64_t dropped_ = 0;
};

}  // namespace climbsim::controller
