#pragma once
/// \file
/// Cholesky factorisation and solves for the stacked EKF's innovation covariance S (3M x 3M),
/// with the method that suits the size: below kBlockedFromSize plain loops (a right-looking
/// factorisation down contiguous columns, solves on a row-major right-hand side);
/// from there on Eigen's blocked LLT, which wins once the matrix outgrows the caches' sweet
/// spot. The threshold was measured with bench/core_bench.cpp (StackedEkfUpdate).
///
/// Buffers grow to the largest size seen and are reused: no allocation once sized.

#include <Eigen/Cholesky>
#include <cmath>
#include <vector>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <int N>
class StackedCholesky {
 public:
  using RowMajorRhs = Eigen::Matrix<double, Eigen::Dynamic, N, Eigen::RowMajor>;
  static constexpr Eigen::Index kBlockedFromSize = 36;

  /// Factorises the symmetric matrix `a` (lower triangle read). False if not positive definite.
  bool compute(const Eigen::MatrixXd& a) {
    size_ = a.rows();
    if (size_ >= kBlockedFromSize) {
      blocked_.compute(a);
      return blocked_.info() == Eigen::Success;
    }
    if (l_.rows() < size_) {
      l_.resize(size_, size_);
      inv_diag_.resize(size_);
    }
    // Right-looking on a column-major copy: once column k is scaled, the trailing lower
    // triangle takes a rank-1 update whose inner loop runs down contiguous columns.
    for (Eigen::Index c = 0; c < size_; ++c) {
      for (Eigen::Index r = c; r < size_; ++r) l_(r, c) = a(r, c);
    }
    for (Eigen::Index k = 0; k < size_; ++k) {
      double* col_k = &l_(0, k);
      const double d = col_k[k];
      if (!(d > 0.0) || !std::isfinite(d)) return false;
      const double pivot = std::sqrt(d);
      col_k[k] = pivot;
      inv_diag_(k) = 1.0 / pivot;
      for (Eigen::Index i = k + 1; i < size_; ++i) col_k[i] *= inv_diag_(k);
      for (Eigen::Index j = k + 1; j < size_; ++j) {
        const double ljk = col_k[j];
        double* col_j = &l_(0, j);
        for (Eigen::Index i = j; i < size_; ++i) col_j[i] -= col_k[i] * ljk;
      }
    }
    return true;
  }

  /// B <- S^-1 B for an m x N row-major B.
  void solve_in_place(RowMajorRhs& b) const {
    if (size_ >= kBlockedFromSize) {
      blocked_.solveInPlace(b);
      return;
    }
    for (Eigen::Index i = 0; i < size_; ++i) {  // L W = B
      auto row = b.row(i);
      for (Eigen::Index k = 0; k < i; ++k) row -= l_(i, k) * b.row(k);
      row *= inv_diag_(i);
    }
    for (Eigen::Index i = size_ - 1; i >= 0; --i) {  // L^T X = W
      auto row = b.row(i);
      for (Eigen::Index k = i + 1; k < size_; ++k) row -= l_(k, i) * b.row(k);
      row *= inv_diag_(i);
    }
  }

  /// v <- S^-1 v.
  void solve_in_place(Eigen::VectorXd& v) const {
    if (size_ >= kBlockedFromSize) {
      blocked_.solveInPlace(v);
      return;
    }
    for (Eigen::Index i = 0; i < size_; ++i) {
      double s = v(i);
      for (Eigen::Index k = 0; k < i; ++k) s -= l_(i, k) * v(k);
      v(i) = s * inv_diag_(i);
    }
    for (Eigen::Index i = size_ - 1; i >= 0; --i) {
      double s = v(i);
      for (Eigen::Index k = i + 1; k < size_; ++k) s -= l_(k, i) * v(k);
      v(i) = s * inv_diag_(i);
    }
  }

  /// Sizes the buffers for an m x m matrix ahead of the first compute().
  void reserve(Eigen::Index m) {
    if (m >= kBlockedFromSize) {
      blocked_ = Eigen::LLT<Eigen::MatrixXd>(m);
    } else if (l_.rows() < m) {
      l_.resize(m, m);
      inv_diag_.resize(m);
    }
  }

 private:
  Eigen::Index size_ = 0;
  Eigen::MatrixXd l_;  // column-major; its lower triangle holds L
  Eigen::VectorXd inv_diag_;
  Eigen::LLT<Eigen::MatrixXd> blocked_;
};

}  // namespace skyfuse
