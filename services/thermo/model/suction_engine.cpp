#include "suction_engine.hpp"

namespace climbsim::thermo {

EngineFlow suctionEngineFlow(const SuctionEngineParams& engine, const GasParams& gas, double speed,
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

}  // namespace climbsim::thermo
