#pragma once
/// @file
/// The drive service without DDS: input holding and validation of `climbsim-drive`
/// (docs/design.md#models). main.cpp only moves samples in and out.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "drive_model.hpp"
#include "robot.h"
#include "thermo.h"

namespace climbsim::drive {

/// Which inputs `climbsim-drive` reads; an absent one keeps its default for the whole run.
struct DriveNodeInputs {
  bool command = true;   ///< "controller/DriveCommand"; default: standing still
  bool adhesion = true;  ///< "thermo/AdhesionForce"; default: --downforce at the centre
};

/// Parses "command,adhesion" (any subset, "none" for none); ConfigError naming --inputs.
DriveNodeInputs parseDriveNodeInputs(const std::string& list);

/// The adhesion force the drive takes before thermo's first AdhesionForce arrives (thermo's
/// output of step 0, read at step 1) [N]: at t = 0 every chamber is at ambient pressure
/// (thermo's initial state, trace row 0), so F = 0. Taking the robot's desired downforce
/// instead would press the chassis into the wall with 2.2 kN in the first step of every run
/// (656 N on each wheel for 15 ms with no vacuum yet).
inline constexpr double kAdhesionForceBeforeThermo_n = 0.0;

/// Input holding and stepping of the drive service. A DriveCommand or AdhesionForce sample
/// that makes the inputs unusable (checkInputs gives the reason: NaN, absurd speeds, wrong
/// wheel count, P_F off the robot) is logged, counted and dropped; the last valid input is
/// held. Several producers of a topic: applied in the order given (producer name). A body
/// command with a sideways speed the robot's fixed wheels cannot give (sidewaysNote) is
/// applied, and said once in the log.
class DriveNode {
 public:
  using Model = DriveModel;  ///< the model it steps (model_contract.hpp)

  /// The robot starts at `start`, standing still, with `downforce_n` at the centre until an
  /// AdhesionForce arrives. ConfigError for bad parameters or a bad default downforce.
  DriveNode(const DriveParams& params, const WallOrientation& wall, const StartPose& start, double downforce_n);

  /// One due step [t_ns, t_ns + dt_ns): merges the samples into the held inputs, steps the
  /// model and returns its outputs at t_ns + dt_ns. The first step makes the model's initial
  /// state at t_ns; each later one must start where the last ended.
  const DriveOutputs& step(std::int64_t t_ns, std::int64_t dt_ns, const std::vector<climbsim::DriveCommand>& commands,
                           const std::vector<climbsim::AdhesionForce>& adhesion);

  /// Steps starting before t_ns keep the chassis at its start pose (DriveInputs::held).
  void holdUntil(std::int64_t t_ns) { hold_until_ns_ = t_ns; }

  const DriveInputs& heldInputs() const { return inputs_; }
  std::uint64_t droppedCommands() const { return dropped_commands_; }
  std::uint64_t droppedAdhesion() const { return dropped_adhesion_; }
  const DriveModel& model() const { return model_; }
  /// The model's state after the last step; empty before the first.
  const std::optional<DriveModelState>& state() const { return state_; }
  /// The outputs before step 0: the start pose at rest (the trace's row 0).
  DriveOutputs initialOutputs() const { return model_.initialState(start_).outputs(); }

 private:
  template <class Sample, class Apply>
  void apply(const std::vector<Sample>& samples, const char* topic, std::uint64_t& dropped, const Apply& apply);

  DriveModel model_;
  StartPose start_;
  std::optional<DriveModelState> state_;
  DriveInputs inputs_;
  std::uint64_t dropped_commands_ = 0;
  std::uint64_t dropped_adhesion_ = 0;
  std::int64_t hold_until_ns_ = 0;
  bool sideways_noted_ = false;
};

}  // namespace climbsim::drive
