#pragma once
/// @file
/// The regularised orifice law of docs/design.md#airflow-and-downforce.

#include <cmath>

namespace climbsim::thermo {

/// Mass flow through an orifice and its slope with respect to the pressure difference.
struct OrificeFlow {
  double mass_flow_kgps = 0.0;    ///< from the high-pressure side: positive when dp > 0
  double dmass_flow_ddp = 0.0;    ///< d(mass_flow)/d(dp) [kg/(s Pa)], >= 0
};

/// Flow through area A [m^2] for dp = p_from - p_to [Pa], density rho [kg/m^3],
/// threshold dp_t [Pa] > 0:
///   |dp| >= dp_t:  mdot = sgn(dp) A sqrt(2 rho |dp|)                     (turbulent)
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

/// orificeFlow() for unit area with the factors that do not depend on dp worked out once,
/// for the integrators' inner loop. Same law; only the rounding of the constant factors
/// differs. Multiply both members of the result by the area.
class OrificeLaw {
 public:
  OrificeLaw(double rho_kgpm3, double threshold_pa)
      : threshold_pa_(threshold_pa),
        inv_threshold_(1.0 / threshold_pa),
        sqrt_2rho_(std::sqrt(2.0 * rho_kgpm3)),
        laminar_scale_(0.25 * std::sqrt(2.0 * rho_kgpm3 * threshold_pa)) {}

  /// Flow per unit area [kg/(s m^2)] at dp [Pa]; the slope only when kSlope (it costs a
  /// division in the turbulent branch), else 0.
  template <bool kSlope>
  OrificeFlow unitFlow(double dp_pa) const {
    const double abs_dp = std::abs(dp_pa);
    if (abs_dp >= threshold_pa_) {
      const double mdot = sqrt_2rho_ * std::sqrt(abs_dp);
      return {dp_pa > 0.0 ? mdot : -mdot, kSlope ? 0.5 * mdot / abs_dp : 0.0};
    }
    const double x = dp_pa * inv_threshold_;
    const double x2 = x * x;
    return {laminar_scale_ * x * (5.0 - x2), kSlope ? laminar_scale_ * (5.0 - 3.0 * x2) * inv_threshold_ : 0.0};
  }

 private:
  double threshold_pa_;
  double inv_threshold_;
  double sqrt_2rho_;
  double laminar_scale_;  // sqrt(2 rho dp_t) / 4
};

}  // namespace climbsim::thermo
