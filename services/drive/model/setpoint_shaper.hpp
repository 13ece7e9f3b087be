#pragma once
/// @file
/// What the drive units' electronics make of the wheel targets, substep by substep: a dead
/// time, a steering rate limit and cosine compensation of the wheel speed. Pure logic, no
/// Simbody; the servos (drive_model) track the references it produces.

#include <cstddef>
#include <deque>
#include <vector>

#include "drive_types.hpp"

namespace climbsim::drive {

/// Reference of one drive unit's servos for the coming substep.
struct UnitReference {
  double steering_rad = 0.0;         ///< rate-limited steering reference δ_ref [rad]
  double steering_rate_radps = 0.0;  ///< its rate over the substep (|.| <= the rate limit)
  double wheel_speed_radps = 0.0;    ///< wheel speed reference ω_ref [rad/s]
};

class SetpointShaper {
 public:
  /// `delay_substeps`: dead time in whole substeps (>= 0); `max_rate_radps` > 0.
  SetpointShaper(std::size_t wheels, int delay_substeps, double max_rate_radps);

  /// One substep of length h_s > 0. `targets` enter the dead time; the targets that leave
  /// it (the initial state, steering 0 and speed 0, during the first delay_substeps) move
  /// the steering reference by at most max_rate * h towards their steering angle, and set
  ///   ω_ref_i = ω_target_i * max(0, 1 - e_max / kAlignmentWindowRad),
  /// e_max the largest |δ_target - δ_ref| of all units: the units roll together, and only
  /// once every wheel points (nearly) where the command needs it, so that a wheel still
  /// turning does not push the robot off its path (the rigid body moves as commanded only
  /// when all wheels agree).
  void advance(const std::vector<WheelSetpoint>& targets, double h_s);

  /// Steering error at which the wheels stop rolling (20°).
  static constexpr double kAlignmentWindowRad = 20.0 * 3.14159265358979323846 / 180.0;

  const std::vector<UnitReference>& references() const { return refs_; }

 private:
  std::size_t delay_;
  double max_rate_radps_;
  std::deque<std::vector<WheelSetpoint>> pipeline_;
  std::vector<UnitReference> refs_;
};

}  // namespace climbsim::drive
