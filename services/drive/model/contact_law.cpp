#include "contact_law.hpp"

#include <cmath>

namespace climbsim::drive {

double normalForce(const ContactParams& c, double wheel_radius_m, double x, double xdot) {
  if (!(x > 0.0)) return 0.0;
  const double elastic = (4.0 / 3.0) * c.hertz_modulus_pa * std::sqrt(wheel_radius_m) * x * std::sqrt(x);
  const double total = elastic * (1.0 + 1.5 * c.dissipation_spm * xdot);
  return total > 0.0 ? total : 0.0;
}

Vec2d frictionForce(const ContactParams& c, const WheelMount& wheel, const Vec2d& z, const Vec2d& v,
                    double normal_force_n) {
  Vec2d f{-(c.tangential_stiffness_npm * z[0] + c.tangential_damping_nspm * v[0]),
          -(c.tangential_stiffness_npm * z[1] + c.tangential_damping_nspm * v[1])};
  const double limit = wheel.friction_coefficient * normal_force_n;
  const double size = std::hypot(f[0], f[1]);
  if (size > limit) {
    const double scale = size > 0.0 ? limit / size : 0.0;
    f[0] *= scale;
    f[1] *= scale;
  }
  return f;
}

Vec2d advanceDeflection(const ContactParams& c, const WheelMount& wheel, const Vec2d& z, const Vec2d& v,
                        double rolling_speed_mps, double normal_force_n, double h_s) {
  if (!(normal_force_n > 0.0)) return {0.0, 0.0};
  const double relax = 1.0 + h_s * std::fabs(rolling_speed_mps) / wheel.relaxation_length_m;
  Vec2d next{(z[0] + h_s * v[0]) / relax, (z[1] + h_s * v[1]) / relax};
  const double limit = wheel.friction_coefficient * normal_force_n / c.tangential_stiffness_npm;
  const double size = std::hypot(next[0], next[1]);
  if (size > limit) {
    next[0] *= limit / size;
    next[1] *= limit / size;
  }
  return next;
}

}  // namespace climbsim::drive
