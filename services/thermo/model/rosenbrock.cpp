#include "rosenbrock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fixed_size.hpp"
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

// Element-wise kernels over the first n entries: the operations of the Eigen expressions in
// their comments, in the same order, as plain loops (Eigen's loops for sizes known only at
// run time were not inlined here and cost a third of the step).
// out = in for vectors of the same size n: the whole capacity, a copy of fixed length that
// compiles to a few moves (a loop of run-time length became a call of memcpy).
// With a size fixed at compile time (kSize > 0) the first kSize entries, a few moves.
template <int kSize = 0>
inline void copyInto(OdeVector& out, const OdeVector& in, int n) {
  static_assert(OdeVector::MaxSizeAtCompileTime == kMaxOdeSize, "OdeVector's storage is kMaxOdeSize doubles");
  (void)n;
  if constexpr (kSize > 0) {
    for (int i = 0; i < kSize; ++i) out[i] = in[i];
  } else {
    std::memcpy(out.data(), in.data(), sizeof(double) * kMaxOdeSize);
  }
}
inline void plusScaled(OdeVector& out, const OdeVector& y, double a, const OdeVector& x, int n) {  // out = y + a x
  for (int i = 0; i < n; ++i) out[i] = y[i] + a * x[i];
}
inline void addScaled(OdeVector& out, double a, const OdeVector& x, int n) {  // out += a x
  for (int i = 0; i < n; ++i) out[i] += a * x[i];
}
inline void scaledDifference(OdeVector& out, double a, const OdeVector& u, const OdeVector& v, int n) {
  for (int i = 0; i < n; ++i) out[i] = a * (u[i] - v[i]);  // out = a (u - v)
}
inline void sumInto(OdeVector& out, const OdeVector& u, const OdeVector& v, int n) {  // out = u + v
  for (int i = 0; i < n; ++i) out[i] = u[i] + v[i];
}
inline bool allFinite(const OdeVector& v, int n) {
  bool finite = true;
  for (int i = 0; i < n; ++i) finite = finite && std::isfinite(v[i]);
  return finite;
}

// integrateRosenbrock for a system of kSize entries, kCoupled of them coupled (both > 0), or
// of the system's sizes at run time (both 0).
template <int kSize, int kCoupled>
void integrateSized(const OdeSystem& system, RosenbrockMethod method, double t_end_s, OdeVector& y,
                    double& step_s, const StepControl& control, IntegratorStats& stats, RhsCarry* carry) {
  static const Tableau kRos2 = ros2();
  static const Tableau kRodas3 = rodas3();
  const Tableau& tab = method == RosenbrockMethod::kRos2 ? kRos2 : kRodas3;
  AdaptiveSteps steps(control, tab.error_order, 6.0, "Rosenbrock", t_end_s, step_s);

  const int size = fixedOr<kSize>(system.size());
  const int coupled = fixedOr<kCoupled>(system.coupledSize());
  const int components = errorComponents(control, system);
  // The error norm over the coupled entries (the default) with its length fixed where the
  // sizes are: the same sum, unrolled.
  const auto normOf = [&](const OdeVector& e, const OdeVector& y0, const OdeVector& y1) {
    if constexpr (kCoupled > 0) {
      if (components == kCoupled) return errorNorm(e, y0, y1, control, kCoupled);
    }
    return errorNorm(e, y0, y1, control, components);
  };
  OdeVector f0(size), f(size), dfdt(size), y_stage(size), y_new(size), err(size), rhs(size);
  OdeMatrix jac(size, size);
  std::array<OdeVector, kMaxStages> k;
  SmallLu<kMaxOdeSize> lu;
  const auto solve = [&lu](OdeVector& b) {
    if constexpr (kCoupled > 0) {
      lu.template solveSized<kCoupled>(b);
    } else {
      lu.solveInPlace(b);
    }
  };
  if (y.size() != size) throw std::invalid_argument("thermo: Rosenbrock: y has " + std::to_string(y.size()) +
                                                    " entries, the system " + std::to_string(size));
  for (OdeVector& stage : k) stage.resize(size);
  const bool w_capable = method == RosenbrockMethod::kRos2 && control.explicit_below > 0.0;
  RhsCarry local_carry;
  RhsCarry& next = carry && w_capable ? *carry : local_carry;  // f at the start of the next step
  next.f.resize(size);

  double last_stiffness = next.stiffness_bound;
  while (!steps.done()) {
    const double t = steps.t();
    // The Jacobian at the start of the step serves every retry of that step. A step the
    // stiffness bound lets go explicit needs only f; when the last step's bound says this
    // one will not, the Jacobian comes first and gives the bound itself.
    bool have_jacobian = false;
    double stiffness = 0.0;
    const auto ensureJacobian = [&] {
      if (have_jacobian) return;
      system.jacobian(t, y, f0, jac, dfdt);
      ++stats.jacobian_evals;
      have_jacobian = true;
      if (w_capable) stiffness = system.stiffnessBound(jac);
    };
    if (next.valid) {
      copyInto<kSize>(f0, next.f, size);
      stiffness = next.stiffness_bound;
    } else if (w_capable && steps.peekTrial() * last_stiffness < control.explicit_below) {
      stiffness = system.rhsWithStiffness(t, y, f0);
      ++stats.rhs_evals;
    } else {
      ensureJacobian();
    }
    next.valid = false;
    last_stiffness = stiffness;
    next.stiffness_bound = stiffness;
    for (;;) {
      const double h_try = steps.trial();

      if (w_capable && h_try * stiffness < control.explicit_below) {
        // W = 0: the scheme below with J = 0 and f_t = 0 is Heun's method, y_new =
        // y + h (f0 + f1) / 2 with f1 = f(t + h, y + h f0), and the error estimate is
        // y_new - (y + h f0) = h (f1 - f0) / 2. ROS2 has order 2 for any W (a W-method,
        // Verwer et al. 1999), and h rho(J) <= h * bound < explicit_below <= 2 keeps
        // Heun's R(z) = 1 + z + z^2/2 in [1/2, 1] on the real spectrum of this system.
        ++stats.explicit_steps;
        plusScaled(y_stage, y, h_try, f0, size);
        const double stiffness1 = system.rhsWithStiffness(t + h_try, y_stage, f);
        ++stats.rhs_evals;
        scaledDifference(err, 0.5 * h_try, f, f0, size);
        sumInto(y_new, y_stage, err, size);
        const double norm = normOf(err, y, y_new);
        if (steps.judge(norm, std::isfinite(norm) && allFinite(y_new, size), stats)) {
          if (norm <= control.euler_below && h_try * stiffness <= 1.0) {
            // The Euler predictor is accurate enough on its own (local error ~ norm):
            // continuing from it makes f1 the next step's f, saving an evaluation where
            // kinks of the actuators force many short steps.
            copyInto<kSize>(y, y_stage, size);
            copyInto<kSize>(next.f, f, size);
            next.stiffness_bound = stiffness1;
            next.valid = true;
          } else {
            copyInto<kSize>(y, y_new, size);
          }
          break;
        }
        continue;
      }

      // G = I / (h gamma) - J. Its quadrature rows (entries coupled..) have only the
      // diagonal and couplings to the pressures, so only the pressure block is factorised
      // and the quadrature parts of the stages follow by substitution.
      ensureJacobian();
      const double diag = 1.0 / (h_try * tab.gamma);
      const auto g = [&](int i, int j) { return (i == j ? diag : 0.0) - jac(i, j); };
      bool factorised = false;
      if constexpr (kCoupled > 0) {
        factorised = lu.template computeSized<kCoupled>(g);
      } else {
        factorised = lu.compute(g, coupled);
      }
      if (!factorised) steps.fail("singular Newton matrix");
      ++stats.lu_decompositions;
      f = f0;
      for (int i = 0; i < tab.stages; ++i) {
        if (i > 0 && tab.new_f[i]) {
          copyInto<kSize>(y_stage, y, size);
          for (int j = 0; j < i; ++j) {
            if (tab.a[i][j] != 0.0) addScaled(y_stage, tab.a[i][j], k[j], size);
          }
          system.rhs(t + tab.alpha[i] * h_try, y_stage, f);
          ++stats.rhs_evals;
        }
        copyInto<kSize>(rhs, f, size);
        for (int j = 0; j < i; ++j) {
          if (tab.c[i][j] != 0.0) addScaled(rhs, tab.c[i][j] / h_try, k[j], size);
        }
        if (tab.gamma_i[i] != 0.0) addScaled(rhs, h_try * tab.gamma_i[i], dfdt, size);
        solve(rhs);
        for (int q = coupled; q < size; ++q) {
          double r = rhs[q];
          for (int j = 0; j < coupled; ++j) r += jac(q, j) * rhs[j];
          rhs[q] = r / diag;
        }
        copyInto<kSize>(k[i], rhs, size);
      }
      copyInto<kSize>(y_new, y, size);
      for (int i = 0; i < size; ++i) err[i] = 0.0;
      for (int i = 0; i < tab.stages; ++i) {
        if (tab.m[i] != 0.0) addScaled(y_new, tab.m[i], k[i], size);
        if (tab.e[i] != 0.0) addScaled(err, tab.e[i], k[i], size);
      }
      // Filter the estimate through (I - h gamma J)^-1 (Shampine 1982; Hairer & Wanner
      // IV.8): Ros2's embedded formula is not L-stable and reports 0.41 of any stiff
      // transient as error although the main formula damps it, which made the
      // controller resolve every millisecond-scale chamber transient. Non-stiff
      // components pass unchanged to leading order.
      solve(err);
      for (int i = 0; i < coupled; ++i) err[i] *= diag;
      const double norm = normOf(err, y, y_new);
      if (steps.judge(norm, std::isfinite(norm) && allFinite(y_new, size), stats)) {
        copyInto<kSize>(y, y_new, size);
        break;
      }
    }
  }
  step_s = steps.proposal();
}

}  // namespace

void integrateRosenbrock(const OdeSystem& system, RosenbrockMethod method, double t_end_s, OdeVector& y,
                         double& step_s, const StepControl& control, IntegratorStats& stats, RhsCarry* carry) {
  // The airflow's systems (pressures and two quadratures) at their sizes; others at run time.
  const int coupled = system.coupledSize();
  const bool airflow_shape = system.size() == coupled + 2;
  withFixedSize<1, kMaxOdeSize - 2>(airflow_shape ? coupled : 0, [&](auto fixed) {
    constexpr int kCoupled = decltype(fixed)::value;
    integrateSized<kCoupled == 0 ? 0 : kCoupled + 2, kCoupled>(system, method, t_end_s, y, step_s, control, stats,
                                                               carry);
  });
}

}  // namespace climbsim::thermo
