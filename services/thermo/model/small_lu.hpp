#pragma once
/// @file
/// LU with partial pivoting for the integrators' small Newton matrix: its size is set at run
/// time, its storage at compile time (kMax x kMax on the stack), and each size runs loops
/// with compile-time bounds. Eigen's general kernels are several times slower at 8x8, which
/// dominated the implicit step.

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

namespace climbsim::thermo {

/// Factorises P A = L U of an n x n matrix (n <= kMax) in place; solve() then gives A^-1 b.
template <int kMax>
class SmallLu {
 public:
  /// a(i, j) -> element accessor of the n x n matrix to factorise (n in 1..kMax). Returns
  /// false if singular.
  template <class Matrix>
  bool compute(const Matrix& a, int n) {
    n_ = n;
    bool ok = false;
    withSize(n, [&](auto size) { ok = computeFixed<decltype(size)::value>(a); });
    return ok;
  }

  /// b <- A^-1 b for the first n entries of b (b[i] accessor).
  template <class Vector>
  void solveInPlace(Vector& b) const {
    withSize(n_, [&](auto size) { solveFixed<decltype(size)::value>(b); });
  }

  /// compute() for a size N (1..kMax) known at compile time.
  template <int N, class Matrix>
  bool computeSized(const Matrix& a) {
    n_ = N;
    return computeFixed<N>(a);
  }

  /// solveInPlace() after computeSized<N>().
  template <int N, class Vector>
  void solveSized(Vector& b) const {
    solveFixed<N>(b);
  }

 private:
  // Calls f(std::integral_constant<int, n>) for the n in 1..kMax: every size gets loops with
  // compile-time bounds, which unroll (same operations in the same order as runtime bounds).
  template <int N = 1, class F>
  static void withSize(int n, const F& f) {
    if constexpr (N <= kMax) {
      if (n == N) {
        f(std::integral_constant<int, N>{});
      } else {
        withSize<N + 1>(n, f);
      }
    }
  }

  template <int N, class Matrix>
  bool computeFixed(const Matrix& a) {
    for (int i = 0; i < N; ++i) {
      for (int j = 0; j < N; ++j) lu_[i][j] = a(i, j);
    }
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      double best = std::abs(lu_[k][k]);
      for (int i = k + 1; i < N; ++i) {
        const double v = std::abs(lu_[i][k]);
        if (v > best) {
          best = v;
          pivot = i;
        }
      }
      if (!(best > 0.0)) return false;
      perm_[k] = pivot;
      if (pivot != k) std::swap_ranges(lu_[k].begin(), lu_[k].begin() + N, lu_[pivot].begin());
      const double inv = 1.0 / lu_[k][k];
      inv_diag_[k] = inv;
      for (int i = k + 1; i < N; ++i) {
        const double factor = lu_[i][k] * inv;
        lu_[i][k] = factor;
        for (int j = k + 1; j < N; ++j) lu_[i][j] -= factor * lu_[k][j];
      }
    }
    return true;
  }

  template <int N, class Vector>
  void solveFixed(Vector& b) const {
    std::array<double, kMax> x;  // first N used (kMax: perm_ entries are in range for the compiler too)
    for (int i = 0; i < N; ++i) x[i] = b[i];
    for (int k = 0; k < N; ++k) {
      if (perm_[k] != k) std::swap(x[k], x[perm_[k]]);
    }
    for (int i = 1; i < N; ++i) {
      for (int j = 0; j < i; ++j) x[i] -= lu_[i][j] * x[j];
    }
    for (int i = N - 1; i >= 0; --i) {
      for (int j = i + 1; j < N; ++j) x[i] -= lu_[i][j] * x[j];
      x[i] *= inv_diag_[i];  // a multiplication: divisions chained through the substitution
    }
    for (int i = 0; i < N; ++i) b[i] = x[i];
  }

  int n_ = 0;
  // Left uninitialised: compute() writes every entry it uses before solveInPlace() reads it,
  // and zeroing them cost as much as a solve in the integrators' per-interval setup.
  std::array<std::array<double, kMax>, kMax> lu_;
  std::array<int, kMax> perm_;
  std::array<double, kMax> inv_diag_;  // 1 / U(i, i)
};

}  // namespace climbsim::thermo
