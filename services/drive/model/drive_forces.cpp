#include "drive_forces.hpp"

#include <algorithm>
#include <cmath>

namespace climbsim::drive {

double servoTorque(const ServoParams& s, double q_ref, double qdot_ref, double q, double qdot) {
  const double torque = s.kp_nmprad * (q_ref - q) + s.kd_nmsprad * (qdot_ref - qdot);
  return std::clamp(torque, -s.torque_max_nm, s.torque_max_nm);
}

double casterDamping(const DriveParams& p, double swivel_rate_radps) {
  return -p.caster_damping_nmsprad * swivel_rate_radps;
}

SealingDrag sealingDrag(const DriveParams& p, double downforce_n, double vx, double vy, double wz) {
  const double drag_n = p.sealing_drag_coefficient * std::max(0.0, downforce_n);
  if (drag_n <= 0) return {};
  const double eps2 = p.drag_regularisation_mps * p.drag_regularisation_mps;
  const double along = std::sqrt(vx * vx + vy * vy + eps2);
  const double rim_speed = wz * p.body_radius_m;
  return {-drag_n * vx / along, -drag_n * vy / along,
          -drag_n * p.body_radius_m * rim_speed / std::sqrt(rim_speed * rim_speed + eps2)};
}

}  // namespace climbsim::drive
