#pragma once
/// @file
/// Run-time sizes as compile-time constants: the thermo model's inner loops (the airflow's
/// right-hand side, the Rosenbrock step) are compiled once per robot size, so that their
/// loops have constant bounds and their arrays the robot's length, as for a model written
/// for one robot. The operations and their order are those of the loops with run-time
/// bounds: the results are the same bit for bit.

#include <type_traits>

namespace climbsim::thermo {

/// f(std::integral_constant<int, n>{}) for n in kFirst..kLast, else
/// f(std::integral_constant<int, 0>{}) (0: the size is known at run time only).
template <int kFirst, int kLast, class F>
decltype(auto) withFixedSize(int n, F&& f) {
  if constexpr (kFirst > kLast) {
    return f(std::integral_constant<int, 0>{});
  } else {
    if (n == kFirst) return f(std::integral_constant<int, kFirst>{});
    return withFixedSize<kFirst + 1, kLast>(n, f);
  }
}

/// kFixed when it is set (> 0), else the run-time value.
template <int kFixed>
constexpr int fixedOr(int runtime) {
  return kFixed > 0 ? kFixed : runtime;
}

}  // namespace climbsim::thermo
