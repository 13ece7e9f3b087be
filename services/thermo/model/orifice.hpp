#pragma once
/// @file
/// The regularised orifice law of DESIGN.md §3.1.

#include <cmath>

namespace climbsim::thermo {

/// Mass flow through an orifice and its slope with respect to the pressure difference.
struct OrificeFlow {
  double mass_flow_kgps = 0.0;    ///< from the high-pressure side: positive when dp > 0
  double dmass_flow_ddp = 0.0;    ///< d(mass_flow)/d(dp) [kg/(s Pa)], >= 0
};

/// Flow through area A [m^2] for dp = p_from - p_to [Pa], density rho [kg/m^3],
/// threshold dp_t [Pa] > 0:
///   |dp| >= dp_t:  mdot = sgn(dp) A sqrt(2 rho |dp|)                     (turbulent, DESIGN.md)
///   |dp| <  dp_t:  mdot = A sqrt(2 rho dp_t) (5 x - x^3) / 4,  x = dp / dp_t
/// The cubic is odd, nearly linear near 0 (laminar, slope 5/4 of the secant to the
/// threshold) and matches the square root's value (x = 1: 1) and slope (x = 1: 1/2)
/// at |dp| = dp_t, so mdot and d(mdot)/d(dp) are continuous everywhere and the slope
/// stays finite (A sqrt(2 rho / dp_t) 5/4 at dp = 0) where the square root's is infinite.
/// It is monotone: d/dx (5x - x^3)/4 = (5 - 3x^2)/4 > 0 for |x| < 1.
inline OrificeFlow orificeFlow(double area_m2, double dp_pa, double rho_kgpm3, double threshold_pa) {
  const double abs_dp = std::abs(dp_pa);
  if (abs_dp >= threshold_pa) {
    const double unit = std::sqrt(2.0 * rho_kgpm3 * abs_dp);
    const double mdot = area_m2 * unit;
    return {dp_pa > 0.0 ? mdot : -mdot, 0.5 * mdot / abs_dp};
  }
  const double scale = area_m2 * std::sqrt(2.0 * rho_kgpm3 * threshold_pa);
  const double x = dp_pa / threshold_pa;
  return {scale * (5.0 * x - x * x * x) * 0.25, scale * (5.0 - 3.0 * x * x) * 0.25 / threshold_pa};
}

}  // namespace climbsim::thermo
