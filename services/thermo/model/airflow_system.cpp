#include "airflow_system.hpp"

#include <algorithm>
#include <cmath>

#include "orifice.hpp"
#include "suction_engine.hpp"

namespace climbsim::thermo {
namespace {

constexpr int kPorts = kNumVolumes + 1;  // the 8 states and the ambient

// Net mass outflow of every port and, when wanted, its derivatives with respect to the
// 8 pressures and to time.
struct Balance {
  std::array<double, kPorts> outflow{};
  Eigen::Matrix<double, kPorts, kNumVolumes> doutflow_dp;
  std::array<double, kPorts> doutflow_dt{};
};

template <bool kDerivatives>
inline void addConnection(Balance& b, int from, int to, double mdot, double dmdot_ddp, double dmdot_dt) {
  b.outflow[from] += mdot;
  b.outflow[to] -= mdot;
  if constexpr (kDerivatives) {
    // mdot depends on p_from - p_to; the ambient's pressure is fixed and has no column.
    if (from < kNumVolumes) {
      b.doutflow_dp(from, from) += dmdot_ddp;
      b.doutflow_dp(to, from) -= dmdot_ddp;
    }
    if (to < kNumVolumes) {
      b.doutflow_dp(from, to) -= dmdot_ddp;
      b.doutflow_dp(to, to) += dmdot_ddp;
    }
    b.doutflow_dt[from] += dmdot_dt;
    b.doutflow_dt[to] -= dmdot_dt;
  }
}

}  // namespace

AirflowSystem::AirflowSystem(const ThermoParams& params, const std::vector<double>& leak_area_m2,
                             const ActuatorRamp& ramp)
    : params_(params), leak_area_m2_(leak_area_m2), ramp_(ramp) {
  const double krt = params.gas.kappa * params.gas.gas_constant_jpkgk * params.gas.temperature_k;
  for (int i = 0; i < kNumChambers; ++i) dpdt_per_outflow_[i] = krt / params.chamber_volume_m3[i];
  dpdt_per_outflow_[kReservoir] = krt / params.reservoir_volume_m3;
  valve_area_scale_m2_ = params.valve.max_area_m2 * params.valve.discharge_coefficient;
}

void AirflowSystem::rhs(double t_s, const OdeVector& y, OdeVector& dydt) const {
  evaluate<false>(t_s, y, dydt, nullptr, nullptr, nullptr);
}

void AirflowSystem::jacobian(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix& dfdy,
                             OdeVector& dfdt) const {
  evaluate<true>(t_s, y, dydt, &dfdy, &dfdt, nullptr);
}

void AirflowSystem::connectionFlows(double t_s, const OdeVector& y, ConnectionFlows& flows) const {
  OdeVector unused;
  evaluate<false>(t_s, y, unused, nullptr, nullptr, &flows);
}

template <bool kDerivatives>
void AirflowSystem::evaluate(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy, OdeVector* dfdt,
                             ConnectionFlows* flows) const {
  const GasParams& gas = params_.gas;
  const double rho = gas.orifice_density_kgpm3;
  const double threshold = params_.laminar_threshold_pa;
  std::array<double, kPorts> p;
  for (int i = 0; i < kNumVolumes; ++i) p[i] = y[i];
  p[kAmbient] = gas.ambient_pressure_pa;

  Balance b;
  if constexpr (kDerivatives) b.doutflow_dp.setZero();
  if (flows) flows->segment_kgps.resize(params_.segments.size());

  for (std::size_t s = 0; s < params_.segments.size(); ++s) {
    const SealingSegment& seg = params_.segments[s];
    const OrificeFlow f = orificeFlow(leak_area_m2_[s], p[seg.volume_a] - p[seg.volume_b], rho, threshold);
    addConnection<kDerivatives>(b, seg.volume_a, seg.volume_b, f.mass_flow_kgps, f.dmass_flow_ddp, 0.0);
    if (flows) flows->segment_kgps[s] = f.mass_flow_kgps;
  }

  for (int c = 0; c < kNumChambers; ++c) {
    const bool moving = t_s < ramp_.valve_reach_s[c];
    const double opening = moving ? ramp_.valve_opening0[c] + ramp_.valve_rate_per_s[c] * t_s : ramp_.valve_target[c];
    const double area = opening * valve_area_scale_m2_;
    // The law is linear in the area: evaluate it once for unit area.
    const OrificeFlow unit = orificeFlow(1.0, p[c] - p[kReservoir], rho, threshold);
    const double darea_dt = moving ? ramp_.valve_rate_per_s[c] * valve_area_scale_m2_ : 0.0;
    addConnection<kDerivatives>(b, c, kReservoir, area * unit.mass_flow_kgps, area * unit.dmass_flow_ddp,
                                unit.mass_flow_kgps * darea_dt);
    if (flows) flows->valve_kgps[c] = area * unit.mass_flow_kgps;
  }

  double engine_total = 0.0, dengine_dpr = 0.0, dengine_dt = 0.0;
  if (flows) flows->engine_kgps.resize(params_.engines.size());
  for (std::size_t e = 0; e < params_.engines.size(); ++e) {
    const SuctionEngineParams& eng = params_.engines[e];
    const double command = ramp_.engine_speed_command[e];
    const double speed = engineSpeedAfter(ramp_.engine_speed0[e], command, eng.speed_lag_s, t_s);
    const EngineFlow ef = suctionEngineFlow(eng, gas, speed, p[kReservoir]);
    engine_total += ef.mass_flow_kgps;
    if constexpr (kDerivatives) {
      dengine_dpr += ef.dmass_flow_dpr;
      dengine_dt += ef.dmass_flow_dspeed * (command - speed) / eng.speed_lag_s;
    }
    if (flows) flows->engine_kgps[e] = ef.mass_flow_kgps;
  }
  b.outflow[kReservoir] += engine_total;

  for (int i = 0; i < kNumVolumes; ++i) dydt[i] = -dpdt_per_outflow_[i] * b.outflow[i];
  dydt[kAmbientInflowEntry] = b.outflow[kAmbient];
  dydt[kEngineOutflowEntry] = engine_total;

  if constexpr (kDerivatives) {
    b.doutflow_dp(kReservoir, kReservoir) += dengine_dpr;
    b.doutflow_dt[kReservoir] += dengine_dt;
    OdeMatrix& jac = *dfdy;
    jac.setZero();
    for (int i = 0; i < kNumVolumes; ++i) {
      jac.row(i).head<kNumVolumes>() = -dpdt_per_outflow_[i] * b.doutflow_dp.row(i);
      (*dfdt)[i] = -dpdt_per_outflow_[i] * b.doutflow_dt[i];
    }
    jac.row(kAmbientInflowEntry).head<kNumVolumes>() = b.doutflow_dp.row(kAmbient);
    (*dfdt)[kAmbientInflowEntry] = b.doutflow_dt[kAmbient];
    jac(kEngineOutflowEntry, kReservoir) = dengine_dpr;
    (*dfdt)[kEngineOutflowEntry] = dengine_dt;
  }
}

}  // namespace climbsim::thermo
