#include "rosenbrock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "small_lu.hpp"

namespace climbsim::thermo {
namespace {

constexpr int kMaxStages = 4;

struct Tableau {
  int stages;
  double gamma;                                  // diagonal of the Newton matrix
  std::array<std::array<double, kMaxStages>, kMaxStages> a;  // stage inputs
  std::array<std::array<double, kMaxStages>, kMaxStages> c;  // stage couplings / h
  std::array<double, kMaxStages> m;              // solution weights
  std::array<double, kMaxStages> e;              // error weights
  std::array<double, kMaxStages> alpha;          // stage times / h
  std::array<double, kMaxStages> gamma_i;        // f_t weights
  std::array<bool, kMaxStages> new_f;            // stage needs a fresh f evaluation
  double error_order;                            // h_new = h * err^(-1 / error_order)
};

Tableau ros2() {
  const double g = 1.0 + 1.0 / std::sqrt(2.0);
  Tableau t{};
  t.stages = 2;
  t.gamma = g;
  t.a[1][0] = 1.0 / g;
  t.c[1][0] = -2.0 / g;
  t.m = {3.0 / (2.0 * g), 1.0 / (2.0 * g), 0.0, 0.0};
  t.e = {1.0 / (2.0 * g), 1.0 / (2.0 * g), 0.0, 0.0};
  t.alpha = {0.0, 1.0, 0.0, 0.0};
  t.gamma_i = {g, -g, 0.0, 0.0};
  t.new_f = {true, true, false, false};
  t.error_order = 2.0;
  return t;
}

Tableau rodas3() {
  Tableau t{};
  t.stages = 4;
  t.gamma = 0.5;
  t.a[2][0] = 2.0;
  t.a[3][0] = 2.0;
  t.a[3][2] = 1.0;
  t.c[1][0] = 4.0;
  t.c[2][0] = 1.0;
  t.c[2][1] = -1.0;
  t.c[3][0] = 1.0;
  t.c[3][1] = -1.0;
  t.c[3][2] = -8.0 / 3.0;
  t.m = {2.0, 0.0, 1.0, 1.0};
  t.e = {0.0, 0.0, 0.0, 1.0};
  t.alpha = {0.0, 0.0, 1.0, 1.0};
  t.gamma_i = {0.5, 1.5, 0.0, 0.0};
  t.new_f = {true, false, true, true};
  t.error_order = 3.0;
  return t;
}

}  // namespace

void integrateRosenbrock(const OdeSystem& system, RosenbrockMethod method, double t_end_s, OdeVector& y,
                         double& step_s, const StepControl& control, IntegratorStats& stats) {
  static const Tableau kRos2 = ros2();
  static const Tableau kRodas3 = rodas3();
  const Tableau& tab = method == RosenbrockMethod::kRos2 ? kRos2 : kRodas3;
  AdaptiveSteps steps(control, tab.error_order, 6.0, "Rosenbrock", t_end_s, step_s);

  OdeVector f0, f, dfdt, y_stage, y_new, err;
  OdeMatrix jac;
  std::array<OdeVector, kMaxStages> k;
  SmallLu<kCoupledSize> lu;

  while (!steps.done()) {
    const double t = steps.t();
    // The Jacobian at the start of the step serves every retry of that step.
    system.jacobian(t, y, f0, jac, dfdt);
    ++stats.jacobian_evals;
    for (;;) {
      const double h_try = steps.trial();

      // G = I / (h gamma) - J. Its quadrature rows (entries kCoupledSize..) have only the
      // diagonal and couplings to the pressures, so only the pressure block is factorised
      // and the quadrature parts of the stages follow by substitution.
      const double diag = 1.0 / (h_try * tab.gamma);
      const auto g = [&](int i, int j) { return (i == j ? diag : 0.0) - jac(i, j); };
      if (!lu.compute(g)) steps.fail("singular Newton matrix");
      ++stats.lu_decompositions;
      f = f0;
      for (int i = 0; i < tab.stages; ++i) {
        if (i > 0 && tab.new_f[i]) {
          y_stage = y;
          for (int j = 0; j < i; ++j) {
            if (tab.a[i][j] != 0.0) y_stage += tab.a[i][j] * k[j];
          }
          system.rhs(t + tab.alpha[i] * h_try, y_stage, f);
          ++stats.rhs_evals;
        }
        OdeVector rhs = f;
        for (int j = 0; j < i; ++j) {
          if (tab.c[i][j] != 0.0) rhs += (tab.c[i][j] / h_try) * k[j];
        }
        if (tab.gamma_i[i] != 0.0) rhs += (h_try * tab.gamma_i[i]) * dfdt;
        lu.solveInPlace(rhs);
        for (int q = kCoupledSize; q < kOdeSize; ++q) {
          double r = rhs[q];
          for (int j = 0; j < kCoupledSize; ++j) r += jac(q, j) * rhs[j];
          rhs[q] = r / diag;
        }
        k[i] = rhs;
      }
      y_new = y;
      err.setZero();
      for (int i = 0; i < tab.stages; ++i) {
        if (tab.m[i] != 0.0) y_new += tab.m[i] * k[i];
        if (tab.e[i] != 0.0) err += tab.e[i] * k[i];
      }
      // Filter the estimate through (I - h gamma J)^-1 (Shampine 1982; Hairer & Wanner
      // IV.8): Ros2's embedded formula is not L-stable and reports 0.41 of any stiff
      // transient as error although the main formula damps it, which made the
      // controller resolve every millisecond-scale chamber transient. Non-stiff
      // components pass unchanged to leading order.
      lu.solveInPlace(err);
      err.head<kCoupledSize>() *= diag;
      const double norm = errorNorm(err, y, y_new, control);
      if (steps.judge(norm, std::isfinite(norm) && y_new.allFinite(), stats)) {
        y = y_new;
        break;
      }
    }
  }
  step_s = steps.proposal();
}

}  // namespace climbsim::thermo
