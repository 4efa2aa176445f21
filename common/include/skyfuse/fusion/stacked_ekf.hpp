#pragma once
/// \file
/// The centralised fusion of paper 000: one EKF update with every station's measurement
/// stacked, z = [z_1; ...; z_M], H = [H_1; ...; H_M], R = blkdiag(R_1, ..., R_M).
///
/// The innovation covariance S is 3M x 3M, so this is the cost the decentralised scheme avoids.
/// It is done the best standard way all the same (Cholesky solve, block-diagonal R exploited
/// in the Joseph term, buffers sized once per station count) so that the comparison is fair.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <span>

#include "skyfuse/core/stacked_cholesky.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/filters/kalman.hpp"

namespace skyfuse {

/// One station's contribution to the stacked update.
template <typename Sensor>
struct StationObservation {
  int station_id = 0;
  Sensor sensor;
  Vector<Sensor::kMeasDim> z;
  Covariance<Sensor::kMeasDim> noise;
};

template <int N, typename Sensor>
class StackedEkf {
 public:
  static constexpr int kMeasDim = Sensor::kMeasDim;
  /// Columns of the state the measurements depend on; H is stored without the zero rest.
  static constexpr int kCols = jacobian_cols<Sensor>();
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");

  /// Updates `state` with all observations at once. Buffers are resized only when the number
  /// of observations changes, so a run with a fixed station count allocates once.
  UpdateReport update(GaussianState<N>& state,
                      std::span<const StationObservation<Sensor>> observations) {
    const Eigen::Index m = static_cast<Eigen::Index>(observations.size()) * kMeasDim;
    resize(m);

    for (std::size_t i = 0; i < observations.size(); ++i) {
      const auto& obs = observations[i];
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      h_.template middleRows<kMeasDim>(row) =
          obs.sensor.jacobian(state.mean).template leftCols<kCols>();
      innovation_.template segment<kMeasDim>(row) =
          obs.sensor.residual(obs.z, obs.sensor.predict(state.mean));
    }

    // S = H P H^T + R (3M x 3M). Only its lower triangle is read by the factorisation, and H
    // has kCols non-zero columns: S_ij = H_i P_cc H_j^T, with coefficient-wise products (the
    // inner dimension is kCols, where a blocked GEMM would be mostly overhead).
    hp_.noalias() = h_.lazyProduct(state.covariance.template topLeftCorner<kCols, kCols>());
    for (Eigen::Index c = 0; c < m; ++c) {
      const double* hc = h_.data() + c * kCols;  // rows of the row-major H are contiguous
      for (Eigen::Index r = c; r < m; ++r) {
        const double* hpr = hp_.data() + r * kCols;
        double sum = 0.0;
        for (int k = 0; k < kCols; ++k) sum += hpr[k] * hc[k];
        s_(r, c) = sum;
      }
    }
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      s_.template block<kMeasDim, kMeasDim>(row, row) += observations[i].noise;
    }
    if (!s_factor_.compute(s_)) return {NumericalStatus::kNotPositiveDefinite};

    // K^T = S^-1 H P = (S^-1 H_c) P[0:kCols, :]: the solve needs kCols right-hand sides, not N.
    s_inv_h_ = h_;
    s_factor_.solve_in_place(s_inv_h_);
    gain_t_.noalias() = s_inv_h_.lazyProduct(state.covariance.template topRows<kCols>());
    state.mean.noalias() += gain_t_.transpose() * innovation_;

    // Joseph form; K R K^T as a sum over the diagonal blocks of R.
    const Matrix<N, kCols> kh = gain_t_.transpose().lazyProduct(h_);
    Covariance<N> joseph = joseph_without_noise<N, kCols>(state.covariance, kh);
    // K R K^T = sum_i K_i R_i K_i^T, symmetric: accumulate the upper triangle only.
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      const Matrix<N, kMeasDim> k_i = gain_t_.template middleRows<kMeasDim>(row).transpose();
      const Matrix<N, kMeasDim> kr = k_i.lazyProduct(observations[i].noise);
      for (int c = 0; c < N; ++c) {
        for (int r = 0; r <= c; ++r) joseph(r, c) += kr.row(r).dot(k_i.row(c));
      }
    }
    // The upper triangle now holds the sum; Joseph's own part was symmetric up to rounding.
    for (int c = 0; c < N; ++c) {
      for (int r = c + 1; r < N; ++r) joseph(r, c) = joseph(c, r);
    }
    state.covariance = joseph;

    whitened_ = innovation_;
    s_factor_.solve_in_place(whitened_);
    return {NumericalStatus::kOk, innovation_.dot(whitened_)};
  }

 private:
  void resize(Eigen::Index m) {
    if (h_.rows() == m) return;
    h_.resize(m, kCols);
    innovation_.resize(m);
    whitened_.resize(m);
    hp_.resize(m, kCols);
    s_inv_h_.resize(m, kCols);
    s_.resize(m, m);
    gain_t_.resize(m, N);
    s_factor_.reserve(m);
  }

  Eigen::Matrix<double, Eigen::Dynamic, kCols, Eigen::RowMajor> h_;
  Eigen::VectorXd innovation_;
  Eigen::VectorXd whitened_;
  Eigen::Matrix<double, Eigen::Dynamic, kCols, Eigen::RowMajor> hp_;  // H_c P_cc
  typename StackedCholesky<kCols>::RowMajorRhs s_inv_h_;
  Eigen::MatrixXd s_;
  Eigen::Matrix<double, Eigen::Dynamic, N> gain_t_;
  StackedCholesky<kCols> s_factor_;
};

}  // namespace skyfuse
