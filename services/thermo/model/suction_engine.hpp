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
EngineFlow suctionEngineFlow(const SuctionEngineParams& engine, const GasParams& gas, double speed,
                             double reservoir_pressure_pa);

/// Speed of the first-order lag ds/dt = (s_cmd - s) / tau after time t_s [s] from s0:
///   s(t) = s_cmd + (s0 - s_cmd) exp(-t / tau).
inline double engineSpeedAfter(double speed0, double speed_command, double lag_s, double t_s) {
  return speed_command + (speed0 - speed_command) * std::exp(-t_s / lag_s);
}

}  // namespace climbsim::thermo
