#include "airflow_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "fixed_size.hpp"
#include "orifice.hpp"
#include "suction_engine.hpp"

namespace climbsim::thermo {
namespace {

constexpr int kMaxPorts = kMaxVolumes + 1;  // the pressure states and the ambient

// Net mass outflow of every port and, as the pass wants them, the summed slopes of its
// connections or its derivatives with respect to the pressures and to time. Ports 0..V-1
// are the pressure states, port V the ambient; kVolumes = V when it is fixed at compile time
// (the arrays then have the robot's length), else 0 (the arrays have the capacity, and only
// the entries of the first V + 1 ports and V columns are used). The arrays a pass needs start
// at zero (all of them: cheaper than a memset of a length known at run time).
template <AirflowPass kPass, int kVolumes>
struct Balance {
  static constexpr int kPorts = kVolumes > 0 ? kVolumes + 1 : kMaxPorts;
  using Slopes = std::conditional_t<kVolumes == 0,
                                    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPorts, kMaxVolumes>,
                                    Eigen::Matrix<double, kPorts, (kVolumes > 0 ? kVolumes : 1)>>;

  explicit Balance(int volumes) : volumes(fixedOr<kVolumes>(volumes)) {
    if constexpr (kPass == AirflowPass::kJacobian) {
      if constexpr (kVolumes > 0) {
        doutflow_dp.setZero();
      } else {
        doutflow_dp.setZero(volumes + 1, volumes);
      }
    }
  }

  int volumes;
  std::array<double, kPorts> outflow{};
  // sum over the port's connections of (sqrt(d_port) + sqrt(d_other)) d(mdot)/d(dp), with
  // sqrt_d = sqrt(kappa R T / V) per port (0 for the ambient): see the bound in evaluate.
  struct Unused {};
  std::conditional_t<kPass == AirflowPass::kStiffness, std::array<double, kPorts>, Unused> weighted_conductance{};
  const double* sqrt_d = nullptr;
  std::conditional_t<kPass == AirflowPass::kJacobian, Slopes, Unused> doutflow_dp;
  std::conditional_t<kPass == AirflowPass::kJacobian, std::array<double, kPorts>, Unused> doutflow_dt{};

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

AirflowLayout::AirflowLayout(const ThermoParams& params)
    : volumes(params.volumeCount()),
      ambient_port(params.volumeCount()),
      valves(params.valveCount()),
      reservoir(params.reservoir()),
      law(params.gas.orifice_density_kgpm3, params.laminar_threshold_pa) {
  const double krt = params.gas.kappa * params.gas.gas_constant_jpkgk * params.gas.temperature_k;
  const int chambers = params.chamberCount();
  for (int i = 0; i < chambers; ++i) dpdt_per_outflow[i] = krt / params.chamber_volume_m3[i];
  if (params.has_reservoir) dpdt_per_outflow[reservoir] = krt / params.reservoir_volume_m3;
  valve_area_scale_m2 = params.valve.max_area_m2 * params.valve.discharge_coefficient;
  for (int i = 0; i < volumes; ++i) sqrt_dpdt_per_outflow[i] = std::sqrt(dpdt_per_outflow[i]);
  sqrt_dpdt_per_outflow[ambient_port] = 0.0;  // not a state: no coupling term
  const auto port = [&](int volume) { return volume == kAmbient ? ambient_port : volume; };
  if (params.segments.size() > segment_ports.size()) {
    throw std::invalid_argument("thermo: " + std::to_string(params.segments.size()) + " sealing segments (at most " +
                                std::to_string(segment_ports.size()) + ")");
  }
  for (const SealingSegment& seg : params.segments) segment_ports[segments++] = {port(seg.volume_a), port(seg.volume_b)};
  const std::size_t engines = params.engines.size();
  std::array<int, kMaxEngines> engine_group;  // validate(): at most kMaxEngines
  for (std::size_t e = 0; e < engines; ++e) {
    const int volume = params.engineVolume(e);
    int g = 0;
    while (g < groups && group_volume[g] != volume) ++g;
    if (g == groups) group_volume[groups++] = volume;
    engine_group[e] = g;
  }
  group_begin[0] = 0;
  group_begin[1] = 0;
  for (int g = 0; g < groups; ++g) {
    for (std::size_t e = 0; e < engines; ++e) {
      if (engine_group[e] == g) engine_order[static_cast<std::size_t>(group_begin[g + 1]++)] = static_cast<int>(e);
    }
    if (g + 1 < groups) group_begin[g + 2] = group_begin[g + 1];
  }
}

AirflowSystem::AirflowSystem(const ThermoParams& params, const AirflowLayout& layout,
                             const std::vector<double>& leak_area_m2, const ActuatorRamp& ramp)
    : OdeSystem(layout.volumes + 2, layout.volumes),
      params_(params),
      layout_(layout),
      leak_area_m2_(leak_area_m2),
      ramp_(ramp) {}

void AirflowSystem::rhs(double t_s, const OdeVector& y, OdeVector& dydt) const {
  evaluate<AirflowPass::kFlow>(t_s, y, dydt, nullptr, nullptr, nullptr);
}

double AirflowSystem::rhsWithStiffness(double t_s, const OdeVector& y, OdeVector& dydt) const {
  return evaluate<AirflowPass::kStiffness>(t_s, y, dydt, nullptr, nullptr, nullptr);
}

double AirflowSystem::stiffnessBound(const OdeMatrix& dfdy) const {
  return withFixedSize<1, kMaxVolumes>(layout_.volumes, [&](auto fixed) {
    return stiffnessBoundSized<decltype(fixed)::value>(dfdy);
  });
}

template <int kVolumes>
double AirflowSystem::stiffnessBoundSized(const OdeMatrix& dfdy) const {
  // Row i of D^1/2 L D^1/2 is row i of J = -D L scaled column by column by sqrt(d_j / d_i).
  const int volumes = fixedOr<kVolumes>(layout_.volumes);
  const double* jac = dfdy.data();
  const int stride = volumes + 2;  // column-major, the system's size in rows: (i, j) at i + j * stride
  double bound = 0.0;
  for (int i = 0; i < volumes; ++i) {
    double row = 0.0;
    for (int j = 0; j < volumes; ++j) row += std::abs(jac[i + j * stride]) * layout_.sqrt_dpdt_per_outflow[j];
    bound = std::max(bound, row / layout_.sqrt_dpdt_per_outflow[i]);
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
  return withFixedSize<1, kMaxVolumes>(layout_.volumes, [&](auto fixed) {
    return evaluateSized<kPass, kOutputs, decltype(fixed)::value>(t_s, y, dydt, dfdy, dfdt, flows);
  });
}

template <AirflowPass kPass, bool kOutputs, int kVolumes>
double AirflowSystem::evaluateSized(double t_s, const OdeVector& y, OdeVector& dydt, OdeMatrix* dfdy,
                                    OdeVector* dfdt, ConnectionFlows* flows) const {
  constexpr bool kSlopes = kPass != AirflowPass::kFlow;
  const GasParams& gas = params_.gas;
  const int volumes = fixedOr<kVolumes>(layout_.volumes);
  const int ambient_port = volumes;
  dydt.resize(volumes + 2);
  std::array<double, Balance<kPass, kVolumes>::kPorts> p;
  if constexpr (kVolumes > 0) {
    for (int i = 0; i < kVolumes; ++i) p[i] = y[i];
  } else {
    // The pressures: a copy of fixed length (a few moves; y's storage holds kMaxOdeSize >= kMaxPorts).
    static_assert(OdeVector::MaxSizeAtCompileTime >= kMaxPorts, "y's storage covers every port");
    std::memcpy(p.data(), y.data(), sizeof(double) * kMaxPorts);
  }
  p[ambient_port] = gas.ambient_pressure_pa;

  Balance<kPass, kVolumes> b(volumes);
  if constexpr (kPass == AirflowPass::kStiffness) b.sqrt_d = layout_.sqrt_dpdt_per_outflow.data();
  if constexpr (kOutputs) flows->segment_kgps.resize(layout_.segments);

  const std::size_t num_segments = layout_.segments;
  for (std::size_t s = 0; s < num_segments; ++s) {
    const auto [from, to] = layout_.segment_ports[s];
    const double area = leak_area_m2_[s];
    const OrificeFlow unit = layout_.law.unitFlow<kSlopes>(p[from] - p[to]);
    b.add(from, to, area * unit.mass_flow_kgps, area * unit.dmass_flow_ddp, 0.0);
    if constexpr (kOutputs) flows->segment_kgps[s] = area * unit.mass_flow_kgps;
  }

  if constexpr (kOutputs) flows->valve_kgps.resize(static_cast<std::size_t>(layout_.valves));
  const int reservoir = layout_.reservoir;
  if (layout_.valves > 0) {
    // The reservoir's side of the valves accumulates in locals, the same operations in the
    // same order as Balance::add, so that the loop carries no dependency through memory.
    double r_out = b.outflow[reservoir], r_weighted = 0.0, r_dp = 0.0, r_dt = 0.0;
    if constexpr (kPass == AirflowPass::kStiffness) r_weighted = b.weighted_conductance[reservoir];
    if constexpr (kPass == AirflowPass::kJacobian) r_dp = b.doutflow_dp(reservoir, reservoir), r_dt = b.doutflow_dt[reservoir];
    const double p_reservoir = p[reservoir];
    for (int c = 0; c < layout_.valves; ++c) {
      const bool moving = t_s < ramp_.valve_reach_s[c];
      const double opening = moving ? ramp_.valve_opening0[c] + ramp_.valve_rate_per_s[c] * t_s : ramp_.valve_target[c];
      const double area = opening * layout_.valve_area_scale_m2;
      const OrificeFlow unit = layout_.law.unitFlow<kSlopes>(p[c] - p_reservoir);
      const double darea_dt = moving ? ramp_.valve_rate_per_s[c] * layout_.valve_area_scale_m2 : 0.0;
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
  for (int g = 0; g < layout_.groups; ++g) {
    const int v = layout_.group_volume[g];
    double flow = 0.0, dflow_dp = 0.0, abs_dflow_dp = 0.0, dflow_dt = 0.0;
    for (int k = layout_.group_begin[g]; k < layout_.group_begin[g + 1]; ++k) {
      const auto e = static_cast<std::size_t>(layout_.engine_order[k]);
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
  for (int i = 0; i < volumes; ++i) dydt[i] = -layout_.dpdt_per_outflow[i] * b.outflow[i];
  dydt[inflow_entry] = b.outflow[ambient_port];
  dydt[outflow_entry] = engine_total;

  if constexpr (kPass == AirflowPass::kJacobian) {
    for (int g = 0; g < layout_.groups; ++g) {
      const int v = layout_.group_volume[g];
      b.doutflow_dp(v, v) += sums.dflow_dp[g];
      b.doutflow_dt[v] += sums.dflow_dt[g];
    }
    OdeMatrix& jac_matrix = *dfdy;
    jac_matrix.setZero(volumes + 2, volumes + 2);
    // jac(i, j), column-major with volumes + 2 rows: a constant stride where the size is fixed.
    const auto jac = [data = jac_matrix.data(), rows = volumes + 2](int i, int j) -> double& {
      return data[i + j * rows];
    };
    dfdt->resize(volumes + 2);
    for (int i = 0; i < volumes; ++i) {
      const double scale = -layout_.dpdt_per_outflow[i];
      for (int j = 0; j < volumes; ++j) jac(i, j) = scale * b.doutflow_dp(i, j);
      (*dfdt)[i] = -layout_.dpdt_per_outflow[i] * b.doutflow_dt[i];
    }
    for (int j = 0; j < volumes; ++j) jac(inflow_entry, j) = b.doutflow_dp(ambient_port, j);
    (*dfdt)[inflow_entry] = b.doutflow_dt[ambient_port];
    for (int g = 0; g < layout_.groups; ++g) jac(outflow_entry, layout_.group_volume[g]) = sums.dflow_dp[g];
    (*dfdt)[outflow_entry] = dengine_dt;
  }
  if constexpr (kPass != AirflowPass::kStiffness) {
    return 0.0;
  } else {
    return stiffnessOf<kVolumes>(b.weighted_conductance, sums.abs_dflow_dp);
  }
}

template <int kVolumes, class PortArray>
double AirflowSystem::stiffnessOf(PortArray& weighted_conductance,
                                  const std::array<double, kMaxEngines>& engine_slope) const {
  const int volumes = fixedOr<kVolumes>(layout_.volumes);
  // The pressure block of the Jacobian is J = -D L with D = diag(kappa R T / V_i) and L
  // symmetric (a Laplacian of the conductances g_ij = d(mdot_ij)/d(dp), plus the ambient's
  // and the engines' slopes on the diagonal). J is similar to -D^1/2 L D^1/2, which is
  // symmetric: real eigenvalues <= 0, spectral radius at most its largest absolute row
  // sum d_i sum_k g_ik + sqrt(d_i) sum_j sqrt(d_j) g_ij = sqrt(d_i) sum_k (sqrt(d_i) +
  // sqrt(d_k)) g_ik (Gershgorin; d = 0 for the ambient). On the symmetric form a
  // chamber's coupling to a reservoir 7x its size weighs sqrt(d_R / d_i) ~ 0.4 instead of
  // 1, so the bound is tighter than Gershgorin on J (up to 2 d_i sum_k g_ik).
  for (int g = 0; g < layout_.groups; ++g) {
    const int v = layout_.group_volume[g];
    weighted_conductance[v] += layout_.sqrt_dpdt_per_outflow[v] * engine_slope[g];
  }
  double bound = 0.0;
  for (int i = 0; i < volumes; ++i) {
    bound = std::max(bound, layout_.sqrt_dpdt_per_outflow[i] * weighted_conductance[i]);
  }
  return bound;
}

}  // namespace climbsim::thermo
