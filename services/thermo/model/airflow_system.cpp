#include "airflow_system.hpp"

#include <algorithm>
#include <cmath>

#include "orifice.hpp"
#include "suction_engine.hpp"

namespace climbsim::thermo {
namespace {

constexpr int kPorts = kNumVolumes + 1;  // the 8 states and the ambient

// Net mass outflow of every port and, as the pass wants them, the summed slopes of its
// connections or its derivatives with respect to the 8 pressures and to time.
template <AirflowPass kPass>
struct Balance {
  std::array<double, kPorts> outflow{};
  // sum over the port's connections of (sqrt(d_port) + sqrt(d_other)) d(mdot)/d(dp), with
  // sqrt_d = sqrt(kappa R T / V) per port (0 for the ambient): see the bound in evaluate.
  std::array<double, kPorts> weighted_conductance{};
  const double* sqrt_d = nullptr;
  Eigen::Matrix<double, kPorts, kNumVolumes> doutflow_dp;
  std::array<double, kPorts> doutflow_dt{};

  void add(int from, int to, double mdot, double dmdot_ddp, double dmdot_dt) {
    outflow[from] += mdot;
    outflow[to] -= mdot;
    if constexpr (kPass == AirflowPass::kStiffness) {
      const double weighted = (sqrt_d[from] + sqrt_d[to]) * dmdot_ddp;
      weighted_conductance[from] += weighted;
      weighted_conductance[to] += weighted;
    }
    if constexpr (kPass == AirflowPass::kJacobian) {
      // mdot depends on p_from - p_to; the ambient's pressure is fixed and has no column.
      if (from < kNumVolumes) {
        doutflow_dp(from, from) += dmdot_ddp;
        doutflow_dp(to, from) -= dmdot_ddp;
      }
      if (to < kNumVolumes) {
        doutflow_dp(from, to) -= dmdot_ddp;
        doutflow_dp(to, to) += dmdot_ddp;
      }
      doutflow_dt[from] += dmdot_dt;
      doutflow_dt[to] -= dmdot_dt;
    }
  }
};

}  // namespace

AirflowSystem::AirflowSystem(const ThermoParams& params, const std::vector<double>& leak_area_m2,
                             const ActuatorRamp& ramp)
    : params_(params),
      leak_area_m2_(leak_area_m2),
      ramp_(ramp),
      law_(params.gas.orifice_density_kgpm3, params.laminar_threshold_pa) {
  const double krt = params.gas.kappa * params.gas.gas_constant_jpkgk * params.gas.temperature_k;
  for (int i = 0; i < kNumChambers; ++i) dpdt_per_outflow_[i] = krt / params.chamber_volume_m3[i];
  dpdt_per_outflow_[kReservoir] = krt / params.reservoir_volume_m3;
  valve_area_scale_m2_ = params.valve.max_area_m2 * params.valve.discharge_coefficient;
  for (int i = 0; i < kNumVolumes; ++i) sqrt_dpdt_per_outflow_[i] = std::sqrt(dpdt_per_outflow_[i]);
  sqrt_dpdt_per_outflow_[kAmbient] = 0.0;  // not a state: no coupling term
}

void AirflowSystem::rhs(double t_s, const OdeVector& y, OdeVector& dydt) const {
  evaluate<AirflowPass::kFlow>(t_s, y, dydt, nullptr, nullptr, nullptr);
}

double AirflowSystem::rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const {
  return evaluate<AirflowPass::kStiffness>(t_s, y, dydt, nullptr, nullptr, nullptr);
}

double AirflowSystem::stiffnessBound(const OdeMatrix& dfdy) const {
  // Row i of D^1/2 L D^1/2 is row i of J = -D L scaled column by column by sqrt(d_j / d_i).
  double bound = 0.0;
  for (int i = 0; i < kNumVolumes; ++i) {
    double row = 0.0;
    for (int j = 0; j < kNumVolumes; ++j) row += std::abs(dfdy(i, j)) * sqrt_dpdt_per_outflow_[j];
    bound = std::max(bound, row / sqrt_dpdt_per_outflow_[i]);
  }
  return bound;
}

void AirflowSystem::jacobian(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix& dfdy,
                             OdeVector& dfdt) const {
  evaluate<AirflowPass::kJacobian>(t_s, y, dydt, &dfdy, &dfdt, nullptr);
}

void AirflowSystem::connectionFlows(double t_s, const OdeVector& y, ConnectionFlows& flows) const {
  OdeVector unused;
  evaluate<AirflowPass::kFlow, true>(t_s, y, unused, nullptr, nullptr, &flows);
}

template <AirflowPass kPass, bool kOutputs>
double AirflowSystem::evaluate(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy, OdeVector* dfdt,
                               ConnectionFlows* flows) const {
  constexpr bool kSlopes = kPass != AirflowPass::kFlow;
  const GasParams& gas = params_.gas;
  std::array<double, kPorts> p;
  for (int i = 0; i < kNumVolumes; ++i) p[i] = y[i];
  p[kAmbient] = gas.ambient_pressure_pa;

  Balance<kPass> b;
  if constexpr (kPass == AirflowPass::kStiffness) b.sqrt_d = sqrt_dpdt_per_outflow_.data();
  if constexpr (kPass == AirflowPass::kJacobian) b.doutflow_dp.setZero();
  if constexpr (kOutputs) flows->segment_kgps.resize(params_.segments.size());

  const std::size_t num_segments = params_.segments.size();
  for (std::size_t s = 0; s < num_segments; ++s) {
    const SealingSegment& seg = params_.segments[s];
    const double area = leak_area_m2_[s];
    const OrificeFlow unit = law_.unitFlow<kSlopes>(p[seg.volume_a] - p[seg.volume_b]);
    b.add(seg.volume_a, seg.volume_b, area * unit.mass_flow_kgps, area * unit.dmass_flow_ddp, 0.0);
    if constexpr (kOutputs) flows->segment_kgps[s] = area * unit.mass_flow_kgps;
  }

  for (int c = 0; c < kNumChambers; ++c) {
    const bool moving = t_s < ramp_.valve_reach_s[c];
    const double opening = moving ? ramp_.valve_opening0[c] + ramp_.valve_rate_per_s[c] * t_s : ramp_.valve_target[c];
    const double area = opening * valve_area_scale_m2_;
    const OrificeFlow unit = law_.unitFlow<kSlopes>(p[c] - p[kReservoir]);
    const double darea_dt = moving ? ramp_.valve_rate_per_s[c] * valve_area_scale_m2_ : 0.0;
    b.add(c, kReservoir, area * unit.mass_flow_kgps, area * unit.dmass_flow_ddp, unit.mass_flow_kgps * darea_dt);
    if constexpr (kOutputs) flows->valve_kgps[c] = area * unit.mass_flow_kgps;
  }

  double engine_total = 0.0, dengine_dpr = 0.0, engine_slope = 0.0, dengine_dt = 0.0;
  if constexpr (kOutputs) flows->engine_kgps.resize(params_.engines.size());
  for (std::size_t e = 0; e < params_.engines.size(); ++e) {
    const SuctionEngineParams& eng = params_.engines[e];
    const double command = ramp_.engine_speed_command[e];
    if (eng.speed_lag_s != decay_lag_s_ || t_s != decay_t_s_) {
      decay_lag_s_ = eng.speed_lag_s;
      decay_t_s_ = t_s;
      decay_ = std::exp(-(ramp_.engine_t0_s + t_s) / decay_lag_s_);
    }
    const double speed = command + (ramp_.engine_speed0[e] - command) * decay_;  // engineSpeedAfter
    const EngineFlow ef = suctionEngineFlow(eng, gas, speed, p[kReservoir]);
    engine_total += ef.mass_flow_kgps;
    dengine_dpr += ef.dmass_flow_dpr;
    engine_slope += std::abs(ef.dmass_flow_dpr);
    if constexpr (kPass == AirflowPass::kJacobian) dengine_dt += ef.dmass_flow_dspeed * (command - speed) / eng.speed_lag_s;
    if constexpr (kOutputs) flows->engine_kgps[e] = ef.mass_flow_kgps;
  }
  b.outflow[kReservoir] += engine_total;

  for (int i = 0; i < kNumVolumes; ++i) dydt[i] = -dpdt_per_outflow_[i] * b.outflow[i];
  dydt[kAmbientInflowEntry] = b.outflow[kAmbient];
  dydt[kEngineOutflowEntry] = engine_total;

  if constexpr (kPass == AirflowPass::kJacobian) {
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
  if constexpr (kPass != AirflowPass::kStiffness) return 0.0;

  // The pressure block of the Jacobian is J = -D L with D = diag(kappa R T / V_i) and L
  // symmetric (a Laplacian of the conductances g_ij = d(mdot_ij)/d(dp), plus the ambient's
  // and the engines' slopes on the diagonal). J is similar to -D^1/2 L D^1/2, which is
  // symmetric: real eigenvalues <= 0, spectral radius at most its largest absolute row
  // sum d_i sum_k g_ik + sqrt(d_i) sum_j sqrt(d_j) g_ij = sqrt(d_i) sum_k (sqrt(d_i) +
  // sqrt(d_k)) g_ik (Gershgorin; d = 0 for the ambient). On the symmetric form a
  // chamber's coupling to the 7x larger reservoir weighs sqrt(d_R / d_i) ~ 0.4 instead of
  // 1, so the bound is tighter than Gershgorin on J (up to 2 d_i sum_k g_ik).
  b.weighted_conductance[kReservoir] += sqrt_dpdt_per_outflow_[kReservoir] * engine_slope;
  double bound = 0.0;
  for (int i = 0; i < kNumVolumes; ++i) {
    bound = std::max(bound, sqrt_dpdt_per_outflow_[i] * b.weighted_conductance[i]);
  }
  return bound;
}

}  // namespace climbsim::thermo
