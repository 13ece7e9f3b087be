#pragma once
/// @file
/// The drive model (DESIGN.md §1.1): a Simbody multibody model of the robot on the wall.
///  - Chassis on a free mobilizer; its frame is R, its centre of mass com_height_m above it.
///  - Per drive unit a steering body on a pin about R's z through the wheel's contact point
///    (at wheel-axle height) and a wheel on a pin about the steering body's y axis.
///  - Each wheel is a sphere of the wheel radius against the wall's half-space (z < 0 in W):
///    penetration r_w - (centre z), contact point the centre projected on the wall plane,
///    normal W's z; the law of ContactParams (contact_law.hpp) gives the force there.
///  - Gravity along WallOrientation, the adhesion force F along -z at P_F, the sealing drag.
///  - Set-points: body command -> wheel targets (drive_command.hpp) -> dead time and steering
///    rate limit (setpoint_shaper.hpp) -> PD servos with torque limits (drive_forces.hpp).
///
/// Simbody holds the bodies and mobilizers and does the kinematics and the forward dynamics.
/// The applied forces come from one of two backends (DriveParams::contact_backend):
///  - direct (default): the model computes them itself from the kinematics it reads once per
///    state (no Simbody force elements, contact tracker or Measures: their per-stage
///    bookkeeping cost more than the physics) and gets udot from the articulated-body
///    operator (calcAccelerationIgnoringConstraints: the tree has no constraints);
///  - simbody: Simbody's ContactTrackerSubsystem and CompliantContactSubsystem with the
///    WheelWallContact generator and Simbody force elements (simbody_contact_forces.hpp), udot
///    from realizing Stage::Acceleration; the normal force outputs are Simbody's contact
///    forces. Same equations: the reference the direct backend is tested against.
/// Everything else (bodies, set-points, friction state, integration, outputs) is shared.
///
/// Integration: a fixed substep h (DriveParams::substep_s; a step of dt is split into
/// ceil(dt / substep) equal substeps) of semi-implicit (symplectic) Euler on Simbody's state,
///   u' = u + h udot(q, u, z),  q' = q + h N(q) u',  then the friction deflections z and the
/// servo references are advanced from (q', u'). One force evaluation per substep (realize to
/// Velocity and Dynamics, one forward-dynamics solve), so the discrete friction and servo
/// states are exactly what the forces of that substep saw; no error control and no event
/// handling, so equal inputs give bit-identical outputs. It is stable here because every mode
/// is slow against 1/h at 1 kHz: contact normal ~270 rad/s, tangential ~160 rad/s, servos
/// ~220 rad/s (ω h < 2 is the limit of the method).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "drive_params.hpp"
#include "drive_types.hpp"

namespace climbsim::drive {

/// "" if `inputs` are usable, else one line naming the field and its value: the command
/// (checkCommand), a non-finite or absurd downforce (|F| > 1e6 N), a non-finite P_F or one
/// farther than the body diameter from the centre.
std::string checkInputs(const DriveParams& params, const DriveInputs& inputs);

class DriveModel {
 public:
  /// Validates `params` (ConfigError). The robot starts at `start` on the wall surface with
  /// its wheels touching it, steering 0, everything at rest.
  DriveModel(const DriveParams& params, const WallOrientation& wall, const StartPose& start);
  ~DriveModel();
  DriveModel(const DriveModel&) = delete;
  DriveModel& operator=(const DriveModel&) = delete;

  /// Advances [t_ns, t_ns + dt_ns) with `inputs` held and returns the state at t_ns + dt_ns.
  /// The first call fixes the start time; each later call must start where the last ended.
  /// Throws std::invalid_argument for dt_ns <= 0, a gap in time or unusable inputs
  /// (checkInputs: callers drop those before).
  const DriveOutputs& step(std::int64_t t_ns, std::int64_t dt_ns, const DriveInputs& inputs);

  /// While held, the chassis stays at its start pose at rest (the operator's hand or safety
  /// rope before the vacuum has built up); wheels, steering and contact forces still evolve.
  /// Released, it moves under the forces from where it is. Takes effect at the next step.
  void setHeld(bool held);
  bool held() const;

  /// The state after the last step (or the start).
  const DriveOutputs& outputs() const;
  const DriveParams& params() const;
  /// The wheel targets in force (after the body command was converted).
  const std::vector<WheelSetpoint>& targets() const;
  /// Substeps taken so far.
  std::int64_t substeps() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace climbsim::drive
