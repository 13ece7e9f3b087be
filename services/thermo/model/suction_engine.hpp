#pragma once
/// @file
/// Suction engine: fan curve (SuctionEngineParams) and speed lag.

#include <cmath>

#include "thermo_params.hpp"

namespace climbsim::thermo {

/// Mass flow an engine removes from the reservoir and its partial derivatives.
struct EngineFlow {
  double mass_flow_kgps = 0.0;       ///< >= 0, out of the reservoir
  double dmass_flow_dpr = 0.0;       ///< d/d(p_R) [kg/(s Pa)]
  double dmass_flow_dspeed = 0.0;    ///< d/d(speed) [kg/s]
};

/// The fan curve of SuctionEngineParams at speed s in [0, 1] and reservoir pressure p_R:
///   Q = Q_max s (1 - (p_o - p_R) / (dp_max s^2)),  mdot = p_R / (R T) * max(Q, 0).
/// For p_R > p_o the line is simply continued (more flow than at zero pressure rise).
/// Inline: it runs in the integrators' inner loop, once per engine and f evaluation.
inline EngineFlow suctionEngineFlow(const SuctionEngineParams& engine, const GasParams& gas, double speed,
                                    double reservoir_pressure_pa) {
  // Below this speed the engine counts as stopped: the curve's pressure scale s^2 would
  // make its slope blow up while the flow it could give is nil.
  constexpr double kStoppedSpeed = 1e-9;
  if (speed <= kStoppedSpeed) return {};
  const double rise_pa = gas.ambient_pressure_pa - reservoir_pressure_pa;
  const double rise_max_pa = engine.pressure_rise_max_pa * speed * speed;
  if (rise_pa >= rise_max_pa) return {};  // no backflow through a stalled fan
  const double q_max = engine.volume_flow_max_m3ps;
  const double flow_m3ps = q_max * speed * (1.0 - rise_pa / rise_max_pa);
  const double rt = gas.gas_constant_jpkgk * gas.temperature_k;
  const double density = reservoir_pressure_pa / rt;
  EngineFlow out;
  out.mass_flow_kgps = density * flow_m3ps;
  // dQ/dp_R = Q_max s / (dp_max s^2); dQ/ds = Q_max (1 + dp / (dp_max s^2)).
  out.dmass_flow_dpr = flow_m3ps / rt + density * q_max * speed / rise_max_pa;
  out.dmass_flow_dspeed = density * q_max * (1.0 + rise_pa / rise_max_pa);
  return out;
}

/// Speed of the first-order lag ds/dt = (s_cmd - s) / tau after time t_s [s] from s0:
///   s(t) = s_cmd + (s0 - s_cmd) exp(-t / tau).
inline double engineSpeedAfter(double speed0, double speed_command, double lag_s, double t_s) {
  return speed_command + (speed0 - speed_command) * std::exp(-t_s / lag_s);
}

}  // namespace climbsim::thermo
