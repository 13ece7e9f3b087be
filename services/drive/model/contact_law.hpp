#pragma once
/// @file
/// The wheel-wall contact law of ContactParams (drive_params.hpp) with each wheel's μ and σ
/// (WheelMount) as pure functions, shared
/// by the contact forces of the drive model and its per-substep friction state update.
/// Vectors are 2D in the wall plane (W's x and y).

#include <array>

#include "drive_params.hpp"

namespace climbsim::drive {

using Vec2d = std::array<double, 2>;

/// Normal force [N] of a sphere of radius r_w pressed x [m] into the wall at penetration rate
/// xdot [m/s]: N = (4/3) E sqrt(r_w) x^(3/2) (1 + 1.5 c xdot); 0 when x <= 0 or N < 0 (the
/// wheel is being pulled off faster than the material relaxes).
double normalForce(const ContactParams& contact, double wheel_radius_m, double penetration_m,
                   double penetration_rate_mps);

/// Friction force on the wheel [N]: F = -(k_t z + c_t v_slip), scaled down to |F| <= μ N.
Vec2d frictionForce(const ContactParams& contact, const WheelMount& wheel, const Vec2d& deflection_m,
                    const Vec2d& slip_mps, double normal_force_n);

/// The deflection after a substep h [s] (implicit in the relaxation, so stable for any speed):
///   z' = (z + h v_slip) / (1 + h |ω| r_w / σ),  then |z'| <= μ N / k_t (sliding beyond).
/// N = 0 (no contact) clears it.
Vec2d advanceDeflection(const ContactParams& contact, const WheelMount& wheel, const Vec2d& deflection_m,
                        const Vec2d& slip_mps, double rolling_speed_mps, double normal_force_n, double h_s);

}  // namespace climbsim::drive
