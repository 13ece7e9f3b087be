#pragma once
/// @file
/// The explicit reference integrator: Dormand-Prince 5(4) with step-size control. Kept
/// for the benchmark (deliverable 6) and as a cross-check of the implicit integrator.

#include "ode_system.hpp"

namespace climbsim::thermo {

/// Integrates y' = f(t, y) from local time 0 to t_end_s (> 0), in place, with the
/// 7-stage FSAL Dormand-Prince pair (order 5, embedded 4; Hairer, Norsett & Wanner,
/// Solving ODEs I, §II.5). On stiff stretches its step is bounded by stability, not
/// accuracy, which is the point of the comparison.
/// step_s: proposed first step in, proposed next step out.
/// Throws std::runtime_error on step-size underflow or more than control.max_steps steps.
void integrateDormandPrince(const OdeSystem& system, double t_end_s, OdeVector& y, double& step_s,
                            const StepControl& control, IntegratorStats& stats);

}  // namespace climbsim::thermo
