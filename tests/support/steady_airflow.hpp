#pragma once
/// @file
/// Test-only oracle, shared by the thermo, controller and system tests: the steady state of the
/// airflow network of docs/design.md#airflow-and-downforce for fixed leak areas and fixed valve
/// openings, found by a damped Newton iteration on the algebraic mass balance (no time integration,
/// none of the thermo model's code): the orifice law typed in again from orifice.hpp's comment,
/// engines on their linear fan curve at full speed, on the reservoir or on their chamber.

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "thermo_params.hpp"

namespace climbsim::thermo::testing {

/// Pressures [Pa] or net outflows [kg/s] of chambers 1..N, then the reservoir if any.
using Volumes = Eigen::VectorXd;
/// Valve opening of chambers 1..N, each in [0, 1]; entries beyond the robot's valves are unused.
/// The functions below take any container indexable by chamber (std::array, std::vector).
using Openings = std::array<double, kMaxChambers>;

/// The same opening for every valve.
inline Openings uniformOpenings(double opening) {
  Openings o;
  o.fill(opening);
  return o;
}

/// Orifice mass flow [kg/s] from a to b through `area` [m²] at dp = p_a - p_b [Pa]:
/// sign(dp) A sqrt(2 rho |dp|), with the laminar regularisation below `threshold`:
/// A sqrt(2 rho dt) (5x - x³)/4, x = dp / dt.
inline double orificeMassFlow(double area, double dp, double rho, double threshold) {
  if (std::abs(dp) >= threshold) return (dp > 0 ? 1.0 : -1.0) * area * std::sqrt(2.0 * rho * std::abs(dp));
  const double x = dp / threshold;
  return area * std::sqrt(2.0 * rho * threshold) * (5.0 * x - x * x * x) / 4.0;
}

/// Mass flow [kg/s] a suction engine at full speed removes from a volume at `pressure` [Pa]:
/// rho Q with Q = Q_max (1 - (p_o - p) / dp_max), none where Q < 0.
inline double engineMassFlow(const ThermoParams& p, const SuctionEngineParams& e, double pressure) {
  const double q = e.volume_flow_max_m3ps * (1.0 - (p.gas.ambient_pressure_pa - pressure) / e.pressure_rise_max_pa);
  return pressure / (p.gas.gas_constant_jpkgk * p.gas.temperature_k) * std::max(q, 0.0);
}

/// Net mass outflow of each volume (chambers 1..N, the reservoir if any) [kg/s] at `pressure`
/// [Pa], with leak_m2[s] the leakage area of segment s of p.segments and the valves at `opening`.
template <class OpeningList>
Volumes netOutflow(const ThermoParams& p, const std::vector<double>& leak_m2, const OpeningList& opening,
                   const Volumes& pressure) {
  Volumes out = Volumes::Zero(p.volumeCount());
  const double rho = p.gas.orifice_density_kgpm3;
  auto at = [&](int v) { return v == kAmbient ? p.gas.ambient_pressure_pa : pressure[v]; };
  for (std::size_t s = 0; s < p.segments.size(); ++s) {
    const auto& seg = p.segments[s];
    const double m = orificeMassFlow(leak_m2[s], at(seg.volume_a) - at(seg.volume_b), rho, p.laminar_threshold_pa);
    if (seg.volume_a != kAmbient) out[seg.volume_a] += m;
    if (seg.volume_b != kAmbient) out[seg.volume_b] -= m;
  }
  const int r = p.reservoir();
  for (int c = 0; c < p.valveCount(); ++c) {
    const double area = opening[c] * p.valve.max_area_m2 * p.valve.discharge_coefficient;
    const double m = orificeMassFlow(area, pressure[c] - pressure[r], rho, p.laminar_threshold_pa);
    out[c] += m;
    out[r] -= m;
  }
  for (std::size_t e = 0; e < p.engines.size(); ++e) {
    const int v = p.engines[e].chamber == SuctionEngineParams::kPumpsReservoir ? r : p.engines[e].chamber;
    out[v] += engineMassFlow(p, p.engines[e], pressure[v]);
  }
  return out;
}

/// Steady pressures [Pa] for the given leaks and openings. `converged` (optional) reports
/// whether the residual fell below 1e-12 kg/s.
template <class OpeningList>
Volumes steadyPressures(const ThermoParams& p, const std::vector<double>& leak_m2, const OpeningList& opening,
                        bool* converged = nullptr) {
  const int n = p.volumeCount();
  Volumes x = Volumes::Constant(n, p.gas.ambient_pressure_pa - 3000.0);
  if (p.has_reservoir) x[p.reservoir()] = p.gas.ambient_pressure_pa - 15000.0;
  Volumes r = netOutflow(p, leak_m2, opening, x);
  for (int it = 0; it < 300 && r.norm() > 1e-16; ++it) {
    Eigen::MatrixXd jac(n, n);
    for (int j = 0; j < n; ++j) {
      Volumes xp = x;
      xp[j] += 1e-3;
      jac.col(j) = (netOutflow(p, leak_m2, opening, xp) - r) / 1e-3;
    }
    const Volumes dx = jac.fullPivLu().solve(-r);
    double lambda = 1.0;
    for (; lambda > 1e-8; lambda *= 0.5) {
      if (netOutflow(p, leak_m2, opening, x + lambda * dx).norm() < r.norm()) break;
    }
    x += lambda * dx;
    r = netOutflow(p, leak_m2, opening, x);
  }
  if (converged) *converged = r.norm() < 1e-12;
  return x;
}

/// F = sum_i (p_o - p_i) A_i of the steady pressures [N].
inline double steadyDownforce(const ThermoParams& p, const Volumes& pressure) {
  double f = 0.0;
  for (int i = 0; i < p.chamberCount(); ++i) f += (p.gas.ambient_pressure_pa - pressure[i]) * p.chamber_area_m2[i];
  return f;
}

}  // namespace climbsim::thermo::testing
