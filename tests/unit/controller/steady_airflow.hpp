#pragma once
/// @file
/// Test-only oracle: the steady state of the airflow network of DESIGN.md §3.1 for fixed leak
/// areas and fixed valve openings, found by a damped Newton iteration on the algebraic mass
/// balance (no time integration, none of the thermo model's code): the orifice law typed in
/// again from orifice.hpp's comment, engines on their linear fan curve at full speed.

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "thermo_params.hpp"

namespace climbsim::controller::testing {

using Vec8 = Eigen::Matrix<double, 8, 1>;

/// Orifice mass flow from a to b through `area` at dp = p_a - p_b, with the laminar
/// regularisation below `threshold`: A sqrt(2 rho dt) (5x - x³)/4, x = dp / dt.
inline double orificeMassFlow(double area, double dp, double rho, double threshold) {
  if (std::abs(dp) >= threshold) return (dp > 0 ? 1.0 : -1.0) * area * std::sqrt(2.0 * rho * std::abs(dp));
  const double x = dp / threshold;
  return area * std::sqrt(2.0 * rho * threshold) * (5.0 * x - x * x * x) / 4.0;
}

/// Net mass outflow of each volume (chambers 1..7, reservoir) [kg/s].
inline Vec8 netOutflow(const thermo::ThermoParams& p, const std::vector<double>& leak_m2,
                       const std::array<double, 7>& opening, const Vec8& pressure) {
  Vec8 out = Vec8::Zero();
  const double rho = p.gas.orifice_density_kgpm3;
  auto at = [&](int v) { return v == thermo::kAmbient ? p.gas.ambient_pressure_pa : pressure[v]; };
  for (std::size_t s = 0; s < p.segments.size(); ++s) {
    const auto& seg = p.segments[s];
    const double m = orificeMassFlow(leak_m2[s], at(seg.volume_a) - at(seg.volume_b), rho, p.laminar_threshold_pa);
    if (seg.volume_a != thermo::kAmbient) out[seg.volume_a] += m;
    if (seg.volume_b != thermo::kAmbient) out[seg.volume_b] -= m;
  }
  for (int c = 0; c < thermo::kNumChambers; ++c) {
    const double area = opening[c] * p.valve.max_area_m2 * p.valve.discharge_coefficient;
    const double m = orificeMassFlow(area, pressure[c] - pressure[thermo::kReservoir], rho, p.laminar_threshold_pa);
    out[c] += m;
    out[thermo::kReservoir] -= m;
  }
  const double rt = p.gas.gas_constant_jpkgk * p.gas.temperature_k;
  for (const auto& e : p.engines) {
    const double q = e.volume_flow_max_m3ps *
                     (1.0 - (p.gas.ambient_pressure_pa - pressure[thermo::kReservoir]) / e.pressure_rise_max_pa);
    out[thermo::kReservoir] += pressure[thermo::kReservoir] / rt * std::max(q, 0.0);
  }
  return out;
}

/// Steady pressures for the given leaks and openings; `converged` reports the residual test.
inline Vec8 steadyPressures(const thermo::ThermoParams& p, const std::vector<double>& leak_m2,
                            const std::array<double, 7>& opening, bool* converged = nullptr) {
  Vec8 x = Vec8::Constant(p.gas.ambient_pressure_pa - 3000.0);
  x[thermo::kReservoir] = p.gas.ambient_pressure_pa - 15000.0;
  Vec8 r = netOutflow(p, leak_m2, opening, x);
  for (int it = 0; it < 300 && r.norm() > 1e-15; ++it) {
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
inline double steadyDownforce(const thermo::ThermoParams& p, const Vec8& pressure) {
  double f = 0.0;
  for (int i = 0; i < thermo::kNumChambers; ++i) f += (p.gas.ambient_pressure_pa - pressure[i]) * p.chamber_area_m2[i];
  return f;
}

}  // namespace climbsim::controller::testing
