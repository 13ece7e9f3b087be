#include "dormand_prince.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace climbsim::thermo {
namespace {

constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
// Difference between the 5th- and 4th-order weights.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;

}  // namespace

void integrateDormandPrince(const OdeSystem& system, double t_end_s, OdeVector& y, double& step_s,
                            const StepControl& control, IntegratorStats& stats) {
  AdaptiveSteps steps(control, 5.0, 10.0, "Dormand-Prince", t_end_s, step_s);
  const int size = system.size();
  const int components = errorComponents(control, system);
  OdeVector k1(size), k2(size), k3(size), k4(size), k5(size), k6(size), k7(size), y_stage(size), y_new(size), err(size);

  system.rhs(0.0, y, k1);
  ++stats.rhs_evals;
  while (!steps.done()) {
    const double h_try = steps.trial();
    const double t = steps.t();
    y_stage = y + h_try * a21 * k1;
    system.rhs(t + c2 * h_try, y_stage, k2);
    y_stage = y + h_try * (a31 * k1 + a32 * k2);
    system.rhs(t + c3 * h_try, y_stage, k3);
    y_stage = y + h_try * (a41 * k1 + a42 * k2 + a43 * k3);
    system.rhs(t + c4 * h_try, y_stage, k4);
    y_stage = y + h_try * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4);
    system.rhs(t + c5 * h_try, y_stage, k5);
    y_stage = y + h_try * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5);
    system.rhs(t + h_try, y_stage, k6);
    y_new = y + h_try * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6);
    system.rhs(t + h_try, y_new, k7);
    stats.rhs_evals += 6;
    err = h_try * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7);

    const double norm = errorNorm(err, y, y_new, control, components);
    if (steps.judge(norm, std::isfinite(norm) && y_new.allFinite(), stats)) {
      y = y_new;
      k1 = k7;  // first same as last
    }
  }
  step_s = steps.proposal();
}

}  // namespace climbsim::thermo
