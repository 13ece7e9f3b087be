#include "drive_translate.hpp"

#include <stdexcept>

namespace climbsim::drive {

DriveCommand driveCommandFromIdl(const climbsim::DriveCommand& s) {
  DriveCommand c;
  c.vx_mps = s.vx_mps();
  c.vy_mps = s.vy_mps();
  c.wz_radps = s.wz_radps();
  c.steering_rad.assign(s.steering_rad().begin(), s.steering_rad().end());
  c.wheel_speed_radps.assign(s.wheel_speed_radps().begin(), s.wheel_speed_radps().end());
  return c;
}

climbsim::DriveCommand driveCommandToIdl(const DriveCommand& c) {
  climbsim::DriveCommand s;
  s.vx_mps(c.vx_mps);
  s.vy_mps(c.vy_mps);
  s.wz_radps(c.wz_radps);
  if (c.steering_rad.size() > 8 || c.wheel_speed_radps.size() > 8) {
    throw std::invalid_argument("driveCommandToIdl: more than 8 wheels");
  }
  s.steering_rad(std::vector<double>(c.steering_rad));
  s.wheel_speed_radps(std::vector<double>(c.wheel_speed_radps));
  return s;
}

void applyAdhesion(const climbsim::AdhesionForce& s, DriveInputs& inputs) {
  inputs.downforce_n = s.downforce_n();
  inputs.pf_x_m = s.pf_x_m();
  inputs.pf_y_m = s.pf_y_m();
}

climbsim::AdhesionForce adhesionForceToIdl(double downforce_n, double pf_x_m, double pf_y_m) {
  climbsim::AdhesionForce s;
  s.downforce_n(downforce_n);
  s.pf_x_m(pf_x_m);
  s.pf_y_m(pf_y_m);
  return s;
}

climbsim::RobotState robotStateToIdl(const DriveOutputs& o) {
  climbsim::RobotState s;
  for (std::size_t k = 0; k < 3; ++k) {
    s.position_m()[k] = o.position_m[k];
    s.linear_velocity_mps()[k] = o.linear_velocity_mps[k];
    s.angular_velocity_radps()[k] = o.angular_velocity_radps[k];
  }
  for (std::size_t k = 0; k < 4; ++k) s.orientation_wxyz()[k] = o.orientation_wxyz[k];
  s.fell(o.fell);
  return s;
}

void driveStateToIdl(const DriveOutputs& o, climbsim::DriveState& s) {
  if (o.wheels.size() > 8) throw std::invalid_argument("driveStateToIdl: more than 8 wheels");
  s.wheels().resize(o.wheels.size());
  for (std::size_t i = 0; i < o.wheels.size(); ++i) {
    const WheelOutputs& w = o.wheels[i];
    climbsim::WheelState& ws = s.wheels()[i];
    ws.steering_rad(w.steering_rad);
    ws.wheel_speed_radps(w.wheel_speed_radps);
    ws.normal_force_n(w.normal_force_n);
    ws.slip_mps(w.slip_mps);
  }
  s.fell(o.fell);
}

climbsim::DriveState driveStateToIdl(const DriveOutputs& o) {
  climbsim::DriveState s;
  driveStateToIdl(o, s);
  return s;
}

}  // namespace climbsim::drive
