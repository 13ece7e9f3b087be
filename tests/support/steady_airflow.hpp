#pragma once
/// @file
/// Test-only oracle, shared by the thermo, controller and system tests: the steady state of the
/// airflow network of docs/design.md#airflow-and-downforce for fixed leak areas and fixed valve
/// openings, found by a damped Newton iteration on the algebraic mass balance (no time integration,
/// none of the thermo model's code): the orifice law typed in again from orifice.hpp's comment,
/// engines on their linear fan curve at full speed.

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "thermo_params.hpp"

namespace climbsim::thermo::testing {

using Vec8 = Eigen::Matrix<double, 8, 1>;  ///< chambers 1..7, then the reservoir [Pa or kg/s]
using Openings = std::array<double, 7>;    ///< valve opening of chambers 1..7, each in [0, 1]

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

/// Net mass outflow of each volume (chambers 1..7, reservoir) [kg/s] at `pressure` [Pa], with
/// leak_m2[s] the leakage area of segment s of p.segments and the valves at `opening`.
inline Vec8 netOutflow(const ThermoParams& p, const std::vector<double>& leak_m2, const Openings& opening,
                       const Vec8& pressure) {
  Vec8 out = Vec8::Zero();
  const double rho = p.gas.orifice_density_kgpm3;
  auto at = [&](int v) { return v == kAmbient ? p.gas.ambient_pressure_pa : pressure[v]; };
  for (std::size_t s = 0; s < p.segments.size(); ++s) {
    const auto& seg = p.segments[s];
    const double m = orificeMassFlow(leak_m2[s], at(seg.volume_a) - at(seg.volume_b), rho, p.laminar_threshold_pa);
    if (seg.volume_a != kAmbient) out[seg.volume_a] += m;
    if (seg.volume_b != kAmbient) out[seg.volume_b] -= m;
  }
  for (int c = 0; c < kNumChambers; ++c) {
    const double area = opening[c] * p.valve.max_area_m2 * p.valve.discharge_coefficient;
    const double m = orificeMassFlow(area, pressure[c] - pressure[kReservoir], rho, p.laminar_threshold_pa);
    out[c] += m;
    out[kReservoir] -= m;
  }
  const double rt = p.gas.gas_constant_jpkgk * p.gas.temperature_k;
  for (const auto& e : p.engines) {
    const double q =
        e.volume_flow_max_m3ps * (1.0 - (p.gas.ambient_pressure_pa - pressure[kReservoir]) / e.pressure_rise_max_pa);
    out[kReservoir] += pressure[kReservoir] / rt * std::max(q, 0.0);
  }
  return out;
}

/// Steady pressures [Pa] for the given leaks and openings. `converged` (optional) reports
/// whether the residual fell below 1e-12 kg/s.
inline Vec8 steadyPressures(const ThermoParams& p, const std::vector<double>& leak_m2, const Openings& opening,
                            bool* converged = nullptr) {
  Vec8 x = Vec8::Constant(p.gas.ambient_pressure_pa - 3000.0);
  x[kReservoir] = p.gas.ambient_pressure_pa - 15000.0;
  Vec8 r = netOutflow(p, leak_m2, opening, x);
  for (int it = 0; it < 300 && r.norm() > 1e-16; ++it) {
    Eigen::Matrix<double, 8, 8> jac;
    for (int j = 0; j < 8; ++j) {
      Vec8 xp = x;
      xp[j] += 1e-3;
      jac.col(j) = (netOutflow(p, leak_m2, opening, xp) - r) / 1e-3;
    }
    const Vec8 dx = jac.fullPivLu().solve(-r);
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
inline double steadyDownforce(const ThermoParams& p, const Vec8& pressure) {
  double f = 0.0;
  for (int i = 0; i < kNumChambers; ++i) f += (p.gas.ambient_pressure_pa - pressure[i]) * p.chamber_area_m2[i];
  return f;
}

}  // namespace climbsim::thermo::testing
