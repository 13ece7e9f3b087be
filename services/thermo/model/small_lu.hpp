#pragma once
/// @file
/// LU with partial pivoting for the integrators' small fixed-size Newton matrix. Sizes are
/// compile-time so the loops unroll; Eigen's general kernels are several times slower
/// at 8x8, which dominated the implicit step.

#include <array>
#include <cmath>
#include <utility>

namespace climbsim::thermo {

/// Factorises P A = L U of an N x N matrix in place; solve() then gives A^-1 b.
template <int N>
class SmallLu {
 public:
  /// a(i, j) -> element accessor of the matrix to factorise. Returns false if singular.
  template <class Matrix>
  bool compute(const Matrix& a) {
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
      if (pivot != k) std::swap(lu_[k], lu_[pivot]);
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

  /// b <- A^-1 b for the first N entries of b (b[i] accessor).
  template <class Vector>
  void solveInPlace(Vector& b) const {
    std::array<double, N> x;
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

 private:
  // Left uninitialised: compute() writes every entry before solveInPlace() reads it, and
  // zeroing them cost as much as a solve in the integrators' per-interval setup.
  std::array<std::array<double, N>, N> lu_;
  std::array<int, N> perm_;
  std::array<double, N> inv_diag_;  // 1 / U(i, i)
};

}  // namespace climbsim::thermo
