#pragma once
/// \file
/// Cholesky factorisation, solve and inverse for small fixed-size symmetric positive definite
/// matrices (the 9 x 9 information matrices of the fusion). Eigen's LLT is general; at these
/// sizes its column-by-column runtime-sized kernels cost several times the arithmetic, and the
/// fusion does two factorisations and two inversions per step. Here every loop bound is a
/// compile-time constant, so the compiler unrolls and schedules them.
///
///   A = L L^T,   A^-1 = L^-T L^-1,   A x = b  <=>  L w = b, L^T x = w.
///
/// The inverse is computed on its upper triangle and mirrored: exactly symmetric.

#include <cmath>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <int N>
class SmallCholesky {
 public:
  /// Factorises `a` (its lower triangle is read). False, and unusable, if `a` is not
  /// positive definite (a non-positive or non-finite pivot).
  bool compute(const Covariance<N>& a) {
    for (int j = 0; j < N; ++j) {
      double d = a(j, j);
      for (int k = 0; k < j; ++k) d -= l_(j, k) * l_(j, k);
      if (!(d > 0.0) || !std::isfinite(d)) return ok_ = false;
      const double pivot = std::sqrt(d);
      l_(j, j) = pivot;
      inv_diag_(j) = 1.0 / pivot;
      for (int i = j + 1; i < N; ++i) {
        double s = a(i, j);
        for (int k = 0; k < j; ++k) s -= l_(i, k) * l_(j, k);
        l_(i, j) = s * inv_diag_(j);
      }
    }
    return ok_ = true;
  }
  bool ok() const { return ok_; }

  /// x with A x = b.
  Vector<N> solve(const Vector<N>& b) const {
    Vector<N> w;
    for (int i = 0; i < N; ++i) {
      double s = b(i);
      for (int k = 0; k < i; ++k) s -= l_(i, k) * w(k);
      w(i) = s * inv_diag_(i);
    }
    Vector<N> x;
    for (int i = N - 1; i >= 0; --i) {
      double s = w(i);
      for (int k = i + 1; k < N; ++k) s -= l_(k, i) * x(k);
      x(i) = s * inv_diag_(i);
    }
    return x;
  }

  /// A^-1 = L^-T L^-1.
  Covariance<N> inverse() const {
    Covariance<N> l_inv = Covariance<N>::Zero();
    for (int j = 0; j < N; ++j) {
      l_inv(j, j) = inv_diag_(j);
      for (int i = j + 1; i < N; ++i) {
        double sum = 0.0;
        for (int k = j; k < i; ++k) sum += l_(i, k) * l_inv(k, j);
        l_inv(i, j) = -sum * inv_diag_(i);
      }
    }
    Covariance<N> out;
    for (int c = 0; c < N; ++c) {
      for (int r = 0; r <= c; ++r) {
        double sum = 0.0;
        for (int k = c; k < N; ++k) sum += l_inv(k, r) * l_inv(k, c);
        out(r, c) = sum;
        out(c, r) = sum;
      }
    }
    return out;
  }

 private:
  Covariance<N> l_ = Covariance<N>::Zero();
  Vector<N> inv_diag_ = Vector<N>::Zero();  // 1 / L(j, j): divisions are slow, and there are many
  bool ok_ = false;
};

}  // namespace skyfuse
