#pragma once
/// @file
/// The drive model (docs/design.md#models): a Simbody multibody model of the robot on the wall.
///  - Chassis on a free mobilizer; its frame is R, its centre of mass com_height_m above it.
///  - Per drive unit a steering body at the mount (at wheel-axle height) and a wheel on a pin
///    about the steering body's y axis. The steering body is on a pin about R's z for a
///    steerable wheel (servo) and a caster (free, damped; its wheel trails the pin by
///    WheelMount::trail_m), welded to the chassis for a fixed wheel. A caster's wheel is not
///    driven.
///  - Each wheel is a sphere of the wheel radius on what it stands on (DriveParams::ground,
///    wheel_ground.hpp, with the direct backend): the sphere's rest height z_rest over the
///    scene's surface under it, penetration (z_rest - centre z) n_z along the contact normal n,
///    friction in the contact plane (docs/design.md#drive). Without a ground, the wall's
///    half-space (z < 0 in W): penetration r_w - (centre z), contact point the centre projected
///    on the wall plane, normal W's z. The law of ContactParams (contact_law.hpp) gives the
///    force there.
///  - Gravity along WallOrientation, the adhesion force F along -z at P_F, the sealing drag.
///  - Set-points: body command -> wheel targets by the robot's kinematics (drive_command.hpp)
///    -> dead time and steering rate limit (setpoint_shaper.hpp) -> PD servos with torque
///    limits (drive_forces.hpp).
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
#include "climbsim/model_contract.hpp"

namespace climbsim::drive {

/// "" if `inputs` are usable, else one line naming the field and its value: the command
/// (checkCommand), a non-finite or absurd downforce (|F| > 1e6 N), a non-finite P_F or one
/// farther than the body diameter from the centre.
std::string checkInputs(const DriveParams& params, const DriveInputs& inputs);

/// The drive model as a model of the one contract (DriveParams, DriveModelState, DriveInputs,
/// DriveOutputs, `Outputs step(State&, const Inputs&, t_ns, dt_ns)`). It holds the Simbody
/// System built from the params and the wall (bodies, mobilizers and, with the simbody
/// backend, the contact and force subsystems), fixed after construction; everything that
/// evolves is in the caller's DriveModelState. step() is const and keeps nothing between
/// calls: equal states and inputs give bit-identical outputs, from this model or any other
/// built from the same params and wall. (Simbody's System counts realizations internally, so
/// one model is not meant to be stepped from several threads at once.)
class DriveModel {
 public:
  /// The model contract's types (climbsim/model_contract.hpp).
  using Params = DriveParams;
  using State = DriveModelState;
  using Inputs = DriveInputs;
  using Outputs = DriveOutputs;

  /// Validates `params` (ConfigError) and builds the System.
  DriveModel(const DriveParams& params, const WallOrientation& wall);
  ~DriveModel();
  DriveModel(const DriveModel&) = delete;
  DriveModel& operator=(const DriveModel&) = delete;

  /// The robot at `start` on the wall surface with its wheels touching it, steering 0,
  /// everything at rest, no command yet, at clock time t_ns.
  DriveModelState initialState(const StartPose& start, std::int64_t t_ns = 0) const;

  /// Advances `state` over [t_ns, t_ns + dt_ns) with `inputs` held and returns the outputs at
  /// t_ns + dt_ns (also kept as state.outputs()). Throws std::invalid_argument, leaving
  /// `state` unchanged, for dt_ns <= 0, t_ns != state.t_ns(), unusable inputs (checkInputs:
  /// callers drop those before) or a state made by a model of another shape.
  DriveOutputs step(DriveModelState& state, const DriveInputs& inputs, std::int64_t t_ns, std::int64_t dt_ns) const;

  const DriveParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

static_assert(is_model_v<DriveModel>, "DriveModel keeps the model contract");

}  // namespace climbsim::drive
