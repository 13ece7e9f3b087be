#pragma once
/// @file
/// The forces of the drive model other than contact (contact_law.hpp) and gravity, as pure
/// functions of the kinematics: the servo torques of the drive units and the sealing drag.
/// No Simbody; drive_model.cpp applies them to its bodies and mobilities.

#include "drive_params.hpp"

namespace climbsim::drive {

/// PD servo with a torque limit [N m]: τ = clamp(kp (q_ref - q) + kd (qdot_ref - qdot), ±τ_max).
double servoTorque(const ServoParams& servo, double q_ref, double qdot_ref, double q, double qdot);

/// A caster's swivel torque [N m]: τ = -caster_damping_nmsprad δ̇ (no servo).
double casterDamping(const DriveParams& params, double swivel_rate_radps);

/// Sealing drag on the chassis, in W, acting at R's origin.
struct SealingDrag {
  double fx_n = 0.0;         ///< force along W's x [N]
  double fy_n = 0.0;         ///< force along W's y [N]
  double torque_z_nm = 0.0;  ///< yaw torque about W's z [N m]
};

/// The drag of the sealing sliding on the wall (DriveParams): with D = k_d max(F, 0),
///   force  -D v / sqrt(|v|² + v_ε²)               (v: velocity of R's origin along the wall),
///   torque -D R (ω_z R) / sqrt((ω_z R)² + v_ε²)   (R: body radius, ω_z: yaw rate).
SealingDrag sealingDrag(const DriveParams& params, double downforce_n, double vx_mps, double vy_mps,
                        double yaw_rate_radps);

}  // namespace climbsim::drive
