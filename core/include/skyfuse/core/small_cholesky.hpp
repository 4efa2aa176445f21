#pragma once
/// \file
/// Cholesky factorisation, solve and inverse for small fixed-size symmetric positive definite
/// matrices (the 9 x 9 information matrices of the fusion). Eigen's LLT is general; at these
/// sizes its column-by-column runtime-sized kernels cost several times the arithmetic, and the
/// fusion does two factorisations and two inversions per step. Here every loop bound is a
/// compile-time constant and every loop is unrolled completely (SKYFUSE_UNROLL: left to itself
/// GCC kept the loop control of these triangular nests, half the instructions of the sweep's
/// fusion).
///
///   A = L L^T,   A^-1 = L^-T L^-1,   A x = b  <=>  L w = b, L^T x = w.
///
/// The inverse is computed on its upper triangle and mirrored: exactly symmetric.

#include <cmath>

#include "skyfuse/core/types.hpp"
#include "skyfuse/core/unroll.hpp"

namespace skyfuse {

template <int N>
class SmallCholesky {
 public:
  /// Factorises `a` (its lower triangle is read). False, and unusable, if `a` is not
  /// positive definite (a non-positive or non-finite pivot).
  bool compute(const Covariance<N>& a) {
    // Right-looking: after column k of L is scaled, the trailing lower triangle takes a rank-1
    // update whose inner loop runs down contiguous columns: independent operations, which the
    // compiler vectorises, instead of a chain of dependent additions.
    l_ = a;
    SKYFUSE_UNROLL
    for (int k = 0; k < N; ++k) {
      const double d = l_(k, k);
      if (!(d > 0.0) || !std::isfinite(d)) return false;
      const double pivot = std::sqrt(d);
      inv_diag_(k) = 1.0 / pivot;
      l_(k, k) = pivot;
      SKYFUSE_UNROLL
      for (int i = k + 1; i < N; ++i) l_(i, k) *= inv_diag_(k);
      SKYFUSE_UNROLL
      for (int j = k + 1; j < N; ++j) {
        const double ljk = l_(j, k);
        SKYFUSE_UNROLL
        for (int i = j; i < N; ++i) l_(i, j) -= l_(i, k) * ljk;
      }
    }
    return true;
  }

  /// x with A x = b.
  Vector<N> solve(const Vector<N>& b) const {
    Vector<N> x = b;
    SKYFUSE_UNROLL
    for (int k = 0; k < N; ++k) {  // L w = b, column by column
      x(k) *= inv_diag_(k);
      SKYFUSE_UNROLL
      for (int i = k + 1; i < N; ++i) x(i) -= l_(i, k) * x(k);
    }
    SKYFUSE_UNROLL
    for (int k = N - 1; k >= 0; --k) {  // L^T x = w
      double s = x(k);
      SKYFUSE_UNROLL
      for (int i = k + 1; i < N; ++i) s -= l_(i, k) * x(i);
      x(k) = s * inv_diag_(k);
    }
    return x;
  }

  /// log det A = 2 sum_k log L_kk.
  double log_determinant() const {
    double sum = 0.0;
    for (int k = 0; k < N; ++k) sum += std::log(l_(k, k));
    return 2.0 * sum;
  }

  /// A^-1 = L^-T L^-1, with L^-1 column by column (each a forward substitution whose inner
  /// loop runs down a column of L) and the product on the upper triangle, mirrored.
  Covariance<N> inverse() const {
    Covariance<N> l_inv = Covariance<N>::Zero();
    SKYFUSE_UNROLL
    for (int j = 0; j < N; ++j) {
      l_inv(j, j) = 1.0;
      SKYFUSE_UNROLL
      for (int k = j; k < N; ++k) {
        const double xk = l_inv(k, j) * inv_diag_(k);
        l_inv(k, j) = xk;
        SKYFUSE_UNROLL
        for (int i = k + 1; i < N; ++i) l_inv(i, j) -= l_(i, k) * xk;
      }
    }
    Covariance<N> out;
    SKYFUSE_UNROLL
    for (int c = 0; c < N; ++c) {
      SKYFUSE_UNROLL
      for (int r = 0; r <= c; ++r) {
        double sum = 0.0;
        SKYFUSE_UNROLL
        for (int k = c; k < N; ++k) sum += l_inv(k, r) * l_inv(k, c);
        out(r, c) = sum;
        out(c, r) = sum;
      }
    }
    return out;
  }

 private:
  Covariance<N> l_ = Covariance<N>::Zero();  // lower triangle holds L
  Vector<N> inv_diag_ = Vector<N>::Zero();   // 1 / L(k, k): divisions are slow, and many
};

}  // namespace skyfuse
