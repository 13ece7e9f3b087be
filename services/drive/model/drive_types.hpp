#pragma once
/// @file
/// Inputs and outputs of the drive model. Frames as in drive_params.hpp (W: wall, R: robot).

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace climbsim::drive {

/// What the controller asks of the drive. Body mode: velocity of R's origin along R's x and
/// y and yaw rate about R's z. Wheel mode (both vectors hold one value per wheel): steering
/// angle and wheel speed set-points per wheel, replacing the body command.
struct DriveCommand {
  double vx_mps = 0.0;
  double vy_mps = 0.0;
  double wz_radps = 0.0;
  std::vector<double> steering_rad;       ///< wheel mode: steering set-points [rad]
  std::vector<double> wheel_speed_radps;  ///< wheel mode: spin-rate set-points [rad/s]

  bool wheelMode() const { return !steering_rad.empty() || !wheel_speed_radps.empty(); }
};

/// Inputs held over one model step.
struct DriveInputs {
  DriveCommand command;
  /// While true the chassis stays at its start pose at rest (the operator's hand or safety
  /// rope before the vacuum has built up); wheels, steering and contact forces still evolve.
  /// Once false it moves under the forces from where it is.
  bool held = false;
  /// Adhesion force F [N] pulling R towards the wall (along -z of W), applied at P_F.
  double downforce_n = 0.0;
  double pf_x_m = 0.0;  ///< P_F in R, x [m] (in the sealing plane, z = 0)
  double pf_y_m = 0.0;  ///< P_F in R, y [m]
};

/// Per-wheel set-points after the body command has been turned into wheel commands.
struct WheelSetpoint {
  double steering_rad = 0.0;
  double wheel_speed_radps = 0.0;
};

struct WheelOutputs {
  double steering_rad = 0.0;       ///< actual steering angle [rad]
  double wheel_speed_radps = 0.0;  ///< actual spin rate, positive rolls along the heading [rad/s]
  double normal_force_n = 0.0;     ///< wall-to-wheel force along the contact normal (W's z on a level surface) [N], >= 0
  double slip_mps = 0.0;           ///< speed of the wheel's contact point over the wall [m/s], >= 0
};

/// The model's state after a step, at time t_ns.
struct DriveOutputs {
  std::int64_t t_ns = 0;
  std::array<double, 3> position_m{};             ///< origin of R in W [m]
  std::array<double, 4> orientation_wxyz{1, 0, 0, 0};  ///< unit quaternion R -> W
  std::array<double, 3> linear_velocity_mps{};    ///< of R's origin, in W [m/s]
  std::array<double, 3> angular_velocity_radps{}; ///< of R, in W [rad/s]
  std::vector<WheelOutputs> wheels;
  bool fell = false;                               ///< latched; DriveParams fall_*, docs/design.md#drive
};

/// Everything of the drive model that evolves from one step to the next (the model contract's
/// State, docs/design.md#the-model-contract): Simbody's SimTK::State (q, u and, with the simbody
/// backend, the contact and force subsystems' variables), the friction deflections, the set-point
/// pipeline (dead time, rate-limited references), the wheel angle references, the fall bookkeeping,
/// the start pose a held robot is kept at, and the outputs at t_ns. DriveModel::initialState()
/// makes it and DriveModel::step() advances it; the model itself holds nothing that changes.
///
/// A value: copying it is a deep copy (SimTK::State copies its state variables; its cache is
/// rebuilt on the next step), so a caller can save one and step from it again, or step copies
/// with different inputs. A state fits every DriveModel built from the same DriveParams and
/// wall (step() refuses one of another shape). Named DriveModelState because the per-wheel
/// topic type of idl/robot.idl is climbsim::DriveState.
class DriveModelState {
 public:
  DriveModelState(const DriveModelState& other);
  DriveModelState(DriveModelState&& other) noexcept;
  DriveModelState& operator=(const DriveModelState& other);
  DriveModelState& operator=(DriveModelState&& other) noexcept;
  ~DriveModelState();

  /// Clock time the state refers to [ns]: the next step must start here.
  std::int64_t t_ns() const;
  /// The outputs at t_ns (of the last step, or of the start).
  const DriveOutputs& outputs() const;
  /// The wheel targets in force (the last body command converted to wheel set-points).
  const std::vector<WheelSetpoint>& targets() const;
  /// Substeps taken so far.
  std::int64_t substeps() const;

  /// The contents, defined in drive_model.cpp (it holds Simbody types; the model library is
  /// the only code compiled against Simbody's headers, see services/drive/CMakeLists.txt).
  struct Data;

 private:
  friend class DriveModel;
  explicit DriveModelState(std::unique_ptr<Data> data);
  std::unique_ptr<Data> data_;
};

}  // namespace climbsim::drive
