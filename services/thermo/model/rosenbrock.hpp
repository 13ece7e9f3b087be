#pragma once
/// @file
/// Linearly implicit (Rosenbrock) integrators with embedded error estimate and step-size
/// control, for the stiff airflow ODE.

#include "ode_system.hpp"

namespace climbsim::thermo {

/// Which Rosenbrock tableau (Hairer & Wanner, Solving ODEs II, §IV.7; coefficients in the
/// form of Sandu et al. 1997, "Benchmarking stiff ODE solvers for atmospheric chemistry II").
enum class RosenbrockMethod {
  /// 2 stages, order 2 (embedded 1), L-stable, gamma = 1 + 1/sqrt(2) (Verwer et al. 1999).
  /// Stability function R(z) = (1 + (1 - 2 gamma) z) / (1 - gamma z)^2 is in (0, 1) for
  /// every real z < 0: a decaying mode never changes sign, whatever the step.
  kRos2,
  /// 4 stages, order 3 (embedded 2), L-stable and stiffly accurate, gamma = 1/2.
  /// R(z) < 0 for real z < -2.9 (minimum -0.12 near z = -8.3): large steps over a
  /// stiff mode overshoot its equilibrium slightly.
  kRodas3,
};

/// What one integration hands to the next (ROS2 with StepControl::explicit_below > 0).
struct RhsCarry {
  /// f at the end of the integration, valid when the last step continued from its Euler
  /// predictor; the caller clears it unless f is continuous there (same inputs, only the
  /// actuators' rates change).
  bool valid = false;
  OdeVector f;
  /// The last stiffness bound (OdeSystem::rhsWithStiffness or Gershgorin of the Jacobian)
  /// [1/s]: it predicts whether the next step goes explicit, i.e. whether to start with f
  /// alone or with the Jacobian. Only a hint: every step decides on its own bound.
  double stiffness_bound = 0.0;
};

/// Integrates y' = f(t, y) from local time 0 to t_end_s (> 0), in place. Every step
/// solves, for stage i with G = I/(h*gamma) - J(0-of-step):
///   G k_i = f(t + alpha_i h, y + sum_j a_ij k_j) + sum_j (c_ij / h) k_j + h gamma_i f_t
///   y_new = y + sum_i m_i k_i,  error = (I - h gamma J)^-1 sum_i e_i k_i
/// (the filtered estimate, so that damped stiff transients do not shrink the step).
/// Linear invariants w^T f = 0 (the air-mass balance) are kept to round-off because
/// w^T J = 0 and w^T f_t = 0 make every w^T k_i vanish.
/// step_s: proposed first step in, proposed next step out (carry it to the next call).
/// Throws std::runtime_error when the step would fall below control.min_step_s, more than
/// control.max_steps steps are needed, or the Newton matrix is singular.
void integrateRosenbrock(const OdeSystem& system, RosenbrockMethod method, double t_end_s, OdeVector& y,
                         double& step_s, const StepControl& control, IntegratorStats& stats,
                         RhsCarry* carry = nullptr);

}  // namespace climbsim::thermo
