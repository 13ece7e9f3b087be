#include "airflow_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "orifice.hpp"
#include "suction_engine.hpp"

namespace climbsim::thermo {
namespace {

constexpr int kMaxPorts = kMaxVolumes + 1;  // the pressure states and the ambient

// Net mass outflow of every port and, as the pass wants them, the summed slopes of its
// connections or its derivatives with respect to the pressures and to time. Ports 0..V-1
// are the pressure states, port V the ambient; only the entries of the first V + 1 ports
// (and V columns) are used. The arrays a pass needs start at zero (all of them: cheaper
// than a memset of a length known at run time).
template <AirflowPass kPass>
struct Balance {
  explicit Balance(int volumes) : volumes(volumes) {
    if constexpr (kPass == AirflowPass::kJacobian) doutflow_dp.setZero(volumes + 1, volumes);
  }

  int volumes;
  std::array<double, kMaxPorts> outflow{};
  // sum over the port's connections of (sqrt(d_port) + sqrt(d_other)) d(mdot)/d(dp), with
  // sqrt_d = sqrt(kappa R T / V) per port (0 for the ambient): see the bound in evaluate.
  struct Unused {};
  std::conditional_t<kPass == AirflowPass::kStiffness, std::array<double, kMaxPorts>, Unused> weighted_conductance{};
  const double* sqrt_d = nullptr;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPorts, kMaxVolumes> doutflow_dp;
  std::conditional_t<kPass == AirflowPass::kJacobian, std::array<double, kMaxPorts>, Unused> doutflow_dt{};

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
      if (from < volumes) {
        doutflow_dp(from, from) += dmdot_ddp;
        doutflow_dp(to, from) -= dmdot_ddp;
      }
      if (to < volumes) {
        doutflow_dp(from, to) -= dmdot_ddp;
        doutflow_dp(to, to) += dmdot_ddp;
      }
      doutflow_dt[from] += dmdot_dt;
      doutflow_dt[to] -= dmdot_dt;
    }
  }
};

// The engines' slopes summed per group (the volume they pump), where the pass uses them;
// every group's entry is written before it is read.
template <AirflowPass kPass>
struct EngineSums {
  struct Unused {};
  template <bool kUsed>
  using Sums = std::conditional_t<kUsed, std::array<double, kMaxEngines>, Unused>;
  Sums<kPass == AirflowPass::kJacobian> dflow_dp;
  Sums<kPass == AirflowPass::kStiffness> abs_dflow_dp;
  Sums<kPass == AirflowPass::kJacobian> dflow_dt;
};

}  // namespace

AirflowSystem::AirflowSystem(const ThermoParams& params, const std::vector<double>& leak_area_m2,
                             const ActuatorRamp& ramp)
    : OdeSystem(params.volumeCount() + 2, params.volumeCount()),
      params_(params),
      leak_area_m2_(leak_area_m2),
      ramp_(ramp),
      volumes_(params.volumeCount()),
      ambient_port_(params.volumeCount()),
      valves_(params.valveCount()),
      reservoir_(params.reservoir()),
      law_(params.gas.orifice_density_kgpm3, params.laminar_threshold_pa) {
  const double krt = params.gas.kappa * params.gas.gas_constant_jpkgk * params.gas.temperature_k;
  const int chambers = params.chamberCount();
  for (int i = 0; i < chambers; ++i) dpdt_per_outflow_[i] = krt / params.chamber_volume_m3[i];
  if (params.has_reservoir) dpdt_per_outflow_[reservoir_] = krt / params.reservoir_volume_m3;
  valve_area_scale_m2_ = params.valve.max_area_m2 * params.valve.discharge_coefficient;
  for (int i = 0; i < volumes_; ++i) sqrt_dpdt_per_outflow_[i] = std::sqrt(dpdt_per_outflow_[i]);
  sqrt_dpdt_per_outflow_[ambient_port_] = 0.0;  // not a state: no coupling term
  const auto port = [&](int volume) { return volume == kAmbient ? ambient_port_ : volume; };
  if (params.segments.size() > segment_ports_.size()) {
    throw std::invalid_argument("thermo: " + std::to_string(params.segments.size()) + " sealing segments (at most " +
                                std::to_string(segment_ports_.size()) + ")");
  }
  for (const SealingSegment& seg : params.segments) segment_ports_[segments_++] = {port(seg.volume_a), port(seg.volume_b)};
  const std::size_t engines = params.engines.size();
  std::array<int, kMaxEngines> engine_group;  // validate(): at most kMaxEngines
  for (std::size_t e = 0; e < engines; ++e) {
    const int volume = params.engineVolume(e);
    int g = 0;
    while (g < groups_ && group_volume_[g] != volume) ++g;
    if (g == groups_) group_volume_[groups_++] = volume;
    engine_group[e] = g;
  }
  group_begin_[0] = 0;
  group_begin_[1] = 0;
  for (int g = 0; g < groups_; ++g) {
    for (std::size_t e = 0; e < engines; ++e) {
      if (engine_group[e] == g) engine_order_[static_cast<std::size_t>(group_begin_[g + 1]++)] = static_cast<int>(e);
    }
    if (g + 1 < groups_) group_begin_[g + 2] = group_begin_[g + 1];
  }
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
  for (int i = 0; i < volumes_; ++i) {
    double row = 0.0;
    for (int j = 0; j < volumes_; ++j) row += std::abs(dfdy(i, j)) * sqrt_dpdt_per_outflow_[j];
    bound = std::max(bound, row / sqrt_dpdt_per_outflow_[i]);
  }
  return bound;
}

void AirflowSystem::jacobian(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix& dfdy,
                             OdeVector& dfdt) const {
  evaluate<AirflowPass::kJacobian>(t_s, y, dydt, &dfdy, &dfdt, nullptr);
}

void AirflowSystem::connectionFlows(double t_s, const OdeVector& y, ConnectionFlows& flows) const {
  OdeVector unused(size());
  evaluate<AirflowPass::kFlow, true>(t_s, y, unused, nullptr, nullptr, &flows);
}

template <AirflowPass kPass, bool kOutputs>
double AirflowSystem::evaluate(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy, OdeVector* dfdt,
                               ConnectionFlows* flows) const {
  constexpr bool kSlopes = kPass != AirflowPass::kFlow;
  const GasParams& gas = params_.gas;
  const int volumes = volumes_;
  dydt.resize(volumes + 2);
  std::array<double, kMaxPorts> p;
  // The pressures: a copy of fixed length (a few moves; y's storage holds kMaxOdeSize >= kMaxPorts).
  static_assert(OdeVector::MaxSizeAtCompileTime >= kMaxPorts, "y's storage covers every port");
  std::memcpy(p.data(), y.data(), sizeof(double) * kMaxPorts);
  p[ambient_port_] = gas.ambient_pressure_pa;

  Balance<kPass> b(volumes);
  if constexpr (kPass == AirflowPass::kStiffness) b.sqrt_d = sqrt_dpdt_per_outflow_.data();
  if constexpr (kOutputs) flows->segment_kgps.resize(segments_);

  const std::size_t num_segments = segments_;
  for (std::size_t s = 0; s < num_segments; ++s) {
    const auto [from, to] = segment_ports_[s];
    const double area = leak_area_m2_[s];
    const OrificeFlow unit = law_.unitFlow<kSlopes>(p[from] - p[to]);
    b.add(from, to, area * unit.mass_flow_kgps, area * unit.dmass_flow_ddp, 0.0);
    if constexpr (kOutputs) flows->segment_kgps[s] = area * unit.mass_flow_kgps;
  }

  if constexpr (kOutputs) flows->valve_kgps.resize(static_cast<std::size_t>(valves_));
  const int reservoir = reservoir_;
  if (valves_ > 0) {
    // The reservoir's side of the valves accumulates in locals, the same operations in the
    // same order as Balance::add, so that the loop carries no dependency through memory.
    double r_out = b.outflow[reservoir], r_weighted = 0.0, r_dp = 0.0, r_dt = 0.0;
    if constexpr (kPass == AirflowPass::kStiffness) r_weighted = b.weighted_conductance[reservoir];
    if constexpr (kPass == AirflowPass::kJacobian) r_dp = b.doutflow_dp(reservoir, reservoir), r_dt = b.doutflow_dt[reservoir];
    const double p_reservoir = p[reservoir];
    for (int c = 0; c < valves_; ++c) {
      const bool moving = t_s < ramp_.valve_reach_s[c];
      const double opening = moving ? ramp_.valve_opening0[c] + ramp_.valve_rate_per_s[c] * t_s : ramp_.valve_target[c];
      const double area = opening * valve_area_scale_m2_;
      const OrificeFlow unit = law_.unitFlow<kSlopes>(p[c] - p_reservoir);
      const double darea_dt = moving ? ramp_.valve_rate_per_s[c] * valve_area_scale_m2_ : 0.0;
      const double mdot = area * unit.mass_flow_kgps;
      const double dmdot_ddp = area * unit.dmass_flow_ddp;
      b.outflow[c] += mdot;
      r_out -= mdot;
      if constexpr (kPass == AirflowPass::kStiffness) {
        const double weighted = (b.sqrt_d[c] + b.sqrt_d[reservoir]) * dmdot_ddp;
        b.weighted_conductance[c] += weighted;
        r_weighted += weighted;
      }
      if constexpr (kPass == AirflowPass::kJacobian) {
        const double dmdot_dt = unit.mass_flow_kgps * darea_dt;
        b.doutflow_dp(c, c) += dmdot_ddp;
        b.doutflow_dp(reservoir, c) -= dmdot_ddp;
        b.doutflow_dp(c, reservoir) -= dmdot_ddp;
        r_dp += dmdot_ddp;
        b.doutflow_dt[c] += dmdot_dt;
        r_dt -= dmdot_dt;
      }
      if constexpr (kOutputs) flows->valve_kgps[c] = mdot;
    }
    b.outflow[reservoir] = r_out;
    if constexpr (kPass == AirflowPass::kStiffness) b.weighted_conductance[reservoir] = r_weighted;
    if constexpr (kPass == AirflowPass::kJacobian) b.doutflow_dp(reservoir, reservoir) = r_dp, b.doutflow_dt[reservoir] = r_dt;
  }

  // Group by group (the volume they pump), each engine in order; the sums in locals.
  double engine_total = 0.0, dengine_dt = 0.0;
  EngineSums<kPass> sums;
  if constexpr (kOutputs) flows->engine_kgps.resize(params_.engines.size());
  for (int g = 0; g < groups_; ++g) {
    const int v = group_volume_[g];
    double flow = 0.0, dflow_dp = 0.0, abs_dflow_dp = 0.0, dflow_dt = 0.0;
    for (int k = group_begin_[g]; k < group_begin_[g + 1]; ++k) {
      const auto e = static_cast<std::size_t>(engine_order_[k]);
      const SuctionEngineParams& eng = params_.engines[e];
      const double command = ramp_.engine_speed_command[e];
      if (eng.speed_lag_s != decay_lag_s_ || t_s != decay_t_s_) {
        decay_lag_s_ = eng.speed_lag_s;
        decay_t_s_ = t_s;
        decay_ = std::exp(-(ramp_.engine_t0_s + t_s) / decay_lag_s_);
      }
      const double speed = command + (ramp_.engine_speed0[e] - command) * decay_;  // engineSpeedAfter
      const EngineFlow ef = suctionEngineFlow(eng, gas, speed, p[v]);
      engine_total += ef.mass_flow_kgps;
      flow += ef.mass_flow_kgps;
      if constexpr (kPass == AirflowPass::kStiffness) abs_dflow_dp += std::abs(ef.dmass_flow_dpr);
      if constexpr (kPass == AirflowPass::kJacobian) {
        dflow_dp += ef.dmass_flow_dpr;
        const double dt = ef.dmass_flow_dspeed * (command - speed) / eng.speed_lag_s;
        dengine_dt += dt;
        dflow_dt += dt;
      }
      if constexpr (kOutputs) flows->engine_kgps[e] = ef.mass_flow_kgps;
    }
    b.outflow[v] += flow;
    if constexpr (kPass == AirflowPass::kStiffness) sums.abs_dflow_dp[g] = abs_dflow_dp;
    if constexpr (kPass == AirflowPass::kJacobian) {
      sums.dflow_dp[g] = dflow_dp;
      sums.dflow_dt[g] = dflow_dt;
    }
  }

  // Entries after the pressures: the ambient inflow, then the engine outflow.
  const int inflow_entry = volumes, outflow_entry = volumes + 1;
  for (int i = 0; i < volumes; ++i) dydt[i] = -dpdt_per_outflow_[i] * b.outflow[i];
  dydt[inflow_entry] = b.outflow[ambient_port_];
  dydt[outflow_entry] = engine_total;

  if constexpr (kPass == AirflowPass::kJacobian) {
    for (int g = 0; g < groups_; ++g) {
      const int v = group_volume_[g];
      b.doutflow_dp(v, v) += sums.dflow_dp[g];
      b.doutflow_dt[v] += sums.dflow_dt[g];
    }
    OdeMatrix& jac = *dfdy;
    jac.setZero(volumes + 2, volumes + 2);
    dfdt->resize(volumes + 2);
    for (int i = 0; i < volumes; ++i) {
      jac.row(i).head(volumes) = -dpdt_per_outflow_[i] * b.doutflow_dp.row(i);
      (*dfdt)[i] = -dpdt_per_outflow_[i] * b.doutflow_dt[i];
    }
    jac.row(inflow_entry).head(volumes) = b.doutflow_dp.row(ambient_port_);
    (*dfdt)[inflow_entry] = b.doutflow_dt[ambient_port_];
    for (int g = 0; g < groups_; ++g) jac(outflow_entry, group_volume_[g]) = sums.dflow_dp[g];
    (*dfdt)[outflow_entry] = dengine_dt;
  }
  if constexpr (kPass != AirflowPass::kStiffness) {
    return 0.0;
  } else {
    return stiffnessOf(b.weighted_conductance, sums.abs_dflow_dp);
  }
}

double AirflowSystem::stiffnessOf(std::array<double, kMaxVolumes + 1>& weighted_conductance,
                                  const std::array<double, kMaxEngines>& engine_slope) const {
  // The pressure block of the Jacobian is J = -D L with D = diag(kappa R T / V_i) and L
  // symmetric (a Laplacian of the conductances g_ij = d(mdot_ij)/d(dp), plus the ambient's
  // and the engines' slopes on the diagonal). J is similar to -D^1/2 L D^1/2, which is
  // symmetric: real eigenvalues <= 0, spectral radius at most its largest absolute row
  // sum d_i sum_k g_ik + sqrt(d_i) sum_j sqrt(d_j) g_ij = sqrt(d_i) sum_k (sqrt(d_i) +
  // sqrt(d_k)) g_ik (Gershgorin; d = 0 for the ambient). On the symmetric form a
  // chamber's coupling to a reservoir 7x its size weighs sqrt(d_R / d_i) ~ 0.4 instead of
  // 1, so the bound is tighter than Gershgorin on J (up to 2 d_i sum_k g_ik).
  for (int g = 0; g < groups_; ++g) {
    const int v = group_volume_[g];
    weighted_conductance[v] += sqrt_dpdt_per_outflow_[v] * engine_slope[g];
  }
  double bound = 0.0;
  for (int i = 0; i < volumes_; ++i) {
    bound = std::max(bound, sqrt_dpdt_per_outflow_[i] * weighted_conductance[i]);
  }
  return bound;
}

}  // namespace climbsim::thermo
