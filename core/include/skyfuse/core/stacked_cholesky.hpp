#pragma once
/// \file
/// Cholesky factorisation and solves for the stacked EKF's innovation covariance S, a
/// (B M) x (B M) matrix of B x B blocks (one block row per station), with the method that suits
/// the size. Below kBlockedFromSize a block algorithm whose every kernel is a fixed-size B x B
/// product, unrolled by the compiler: at these sizes a scalar loop nest spends more on loop
/// control than on arithmetic. From there on Eigen's blocked LLT, which wins once the matrix
/// outgrows the caches' sweet spot. Measured with bench/core_bench.cpp (StackedEkfUpdate): the
/// block algorithm is faster up to M = 64 (8.8 vs 15 us at M = 16, 42 vs 59 us at M = 32),
/// Eigen's at M = 128 (1.8 vs 2.9 ms); the threshold sits between the two.
///
/// Buffers grow to the largest size seen and are reused: no allocation once sized.

#include <Eigen/Cholesky>
#include <cmath>

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/core/unroll.hpp"

namespace skyfuse {

/// B: the block size (a station's measurement dimension); N: the columns of a right-hand side.
template <int B, int N>
class StackedCholesky {
 public:
  using RowMajorRhs = Eigen::Matrix<double, Eigen::Dynamic, N, Eigen::RowMajor>;
  static constexpr Eigen::Index kBlockedFromSize = 256;

  /// Factorises the symmetric matrix `a` (lower triangle read; its size a multiple of B).
  /// False if it is not positive definite.
  bool compute(const Eigen::MatrixXd& a) {
    size_ = a.rows();
    if (size_ >= kBlockedFromSize) {
      blocked_.compute(a);
      return llt_succeeded(blocked_);
    }
    reserve(size_);
    const Eigen::Index blocks = size_ / B;
    // Left-looking, one block column at a time:
    //   L_jj = chol(A_jj - sum_k L_jk L_jk^T),  L_ij = (A_ij - sum_k L_ik L_jk^T) L_jj^-T.
    for (Eigen::Index j = 0; j < blocks; ++j) {
      Block d = a.template block<B, B>(j * B, j * B);
      for (Eigen::Index k = 0; k < j; ++k) d.noalias() -= l(j, k).lazyProduct(l(j, k).transpose());
      if (!factor_diagonal(j, d)) return false;
      for (Eigen::Index i = j + 1; i < blocks; ++i) {
        Block b = a.template block<B, B>(i * B, j * B);
        for (Eigen::Index k = 0; k < j; ++k) {
          b.noalias() -= l(i, k).lazyProduct(l(j, k).transpose());
        }
        // X L_jj^T = b is L_jj X^T = b^T: a forward substitution on b^T.
        Block x = b.transpose();
        forward_in_block(j, x);
        l(i, j) = x.transpose();
      }
    }
    return true;
  }

  /// X <- S^-1 X for an m x N row-major X.
  void solve_in_place(RowMajorRhs& x) const {
    if (size_ >= kBlockedFromSize) {
      blocked_.solveInPlace(x);
      return;
    }
    forward(x);
    const Eigen::Index blocks = size_ / B;
    for (Eigen::Index i = blocks - 1; i >= 0; --i) {  // L^T X = W, block by block
      BlockRows<N> w = x.template middleRows<B>(i * B);
      for (Eigen::Index k = i + 1; k < blocks; ++k) {
        w.noalias() -= l(k, i).transpose().lazyProduct(x.template middleRows<B>(k * B));
      }
      SKYFUSE_UNROLL
      for (int r = B - 1; r >= 0; --r) {
        SKYFUSE_UNROLL
        for (int q = r + 1; q < B; ++q) w.row(r) -= l_(i * B + q, i * B + r) * w.row(q);
        w.row(r) *= inv_diag_(i * B + r);
      }
      x.template middleRows<B>(i * B) = w;
    }
  }

  /// v <- L^-1 v, the forward half of a solve: v^T S^-1 v = |L^-1 v|^2 needs no more.
  void forward_solve_in_place(Eigen::VectorXd& v) const {
    if (size_ >= kBlockedFromSize) {
      blocked_.matrixL().solveInPlace(v);
      return;
    }
    forward(v);
  }

  /// Sizes the buffers for an m x m matrix ahead of the first compute().
  void reserve(Eigen::Index m) {
    if (m >= kBlockedFromSize) {
      blocked_ = Eigen::LLT<Eigen::MatrixXd>(m);
    } else if (l_.rows() < m) {
      l_.setZero(m, m);
      inv_diag_.resize(m);
    }
  }

 private:
  using Block = Eigen::Matrix<double, B, B>;
  // B rows of a right-hand side with C columns (a vector when C is 1).
  template <int C>
  using BlockRows = Eigen::Matrix<double, B, C, (C == 1 ? Eigen::ColMajor : Eigen::RowMajor)>;

  auto l(Eigen::Index i, Eigen::Index j) { return l_.template block<B, B>(i * B, j * B); }
  auto l(Eigen::Index i, Eigen::Index j) const { return l_.template block<B, B>(i * B, j * B); }

  // The scalar Cholesky of one diagonal block, into L_jj and its reciprocal pivots.
  bool factor_diagonal(Eigen::Index j, Block& d) {
    SKYFUSE_UNROLL
    for (int c = 0; c < B; ++c) {
      SKYFUSE_UNROLL
      for (int q = 0; q < c; ++q) d(c, c) -= d(c, q) * d(c, q);
      if (!(d(c, c) > 0.0) || !std::isfinite(d(c, c))) return false;
      const double pivot = std::sqrt(d(c, c));
      const double inv = 1.0 / pivot;
      d(c, c) = pivot;
      inv_diag_(j * B + c) = inv;
      SKYFUSE_UNROLL
      for (int r = c + 1; r < B; ++r) {
        SKYFUSE_UNROLL
        for (int q = 0; q < c; ++q) d(r, c) -= d(r, q) * d(c, q);
        d(r, c) *= inv;
      }
    }
    l(j, j) = d.template triangularView<Eigen::Lower>();
    return true;
  }

  // L W = X, block by block (X: m x N row-major, or a vector).
  template <typename Rhs>
  void forward(Rhs& x) const {
    constexpr int kCols = Rhs::ColsAtCompileTime;
    const Eigen::Index blocks = size_ / B;
    for (Eigen::Index i = 0; i < blocks; ++i) {
      BlockRows<kCols> w = x.template middleRows<B>(i * B);
      for (Eigen::Index k = 0; k < i; ++k) {
        w.noalias() -= l(i, k).lazyProduct(x.template middleRows<B>(k * B));
      }
      forward_in_block(i, w);
      x.template middleRows<B>(i * B) = w;
    }
  }

  // W <- L_ii^-1 W for the B rows of W: the forward substitution within diagonal block i.
  template <typename Rows>
  void forward_in_block(Eigen::Index i, Rows& w) const {
    SKYFUSE_UNROLL
    for (int r = 0; r < B; ++r) {
      SKYFUSE_UNROLL
      for (int q = 0; q < r; ++q) w.row(r) -= l_(i * B + r, i * B + q) * w.row(q);
      w.row(r) *= inv_diag_(i * B + r);
    }
  }

  Eigen::Index size_ = 0;
  Eigen::MatrixXd l_;  // column-major; its lower block triangle holds L
  Eigen::VectorXd inv_diag_;
  // Factorised from the start, of an empty matrix: Eigen 3.4's default LLT leaves its norm and
  // status unset, and moving the owner before its first factorisation (a tracker is moved into
  // its node) would copy those unset values (GCC's -Wmaybe-uninitialized said so).
  Eigen::LLT<Eigen::MatrixXd> blocked_{Eigen::MatrixXd()};
};

}  // namespace skyfuse
