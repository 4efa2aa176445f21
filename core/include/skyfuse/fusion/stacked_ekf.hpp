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
#include "skyfuse/core/unroll.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/station_observation.hpp"

namespace skyfuse {

template <int N, typename Sensor>
class StackedEkf {
 public:
  static constexpr int kMeasDim = Sensor::kMeasDim;
  /// Columns of the state the measurements depend on; H is stored without the zero rest.
  static constexpr int kCols = jacobian_cols<Sensor>();
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");

  /// Updates `state` with all observations at once (`Observations`: a random-access range of
  /// StationObservation<Sensor>, a span or an IndirectView). Buffers are resized only when the
  /// number of observations changes, so a run with a fixed station count allocates once.
  template <typename Observations>
  UpdateReport update(GaussianState<N>& state, const Observations& observations) {
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

    // S = H P H^T + R (3M x 3M), by blocks: S_ij = (H_i P_cc) H_j^T, fixed-size products over
    // the kCols columns where H is not zero. The factorisation reads the lower triangle only.
    hp_.noalias() = h_.lazyProduct(state.covariance.template topLeftCorner<kCols, kCols>());
    const Eigen::Index blocks = static_cast<Eigen::Index>(observations.size());
    for (Eigen::Index j = 0; j < blocks; ++j) {
      const auto h_j = h_.template middleRows<kMeasDim>(j * kMeasDim);
      for (Eigen::Index i = j; i < blocks; ++i) {
        s_.template block<kMeasDim, kMeasDim>(i * kMeasDim, j * kMeasDim).noalias() =
            hp_.template middleRows<kMeasDim>(i * kMeasDim).lazyProduct(h_j.transpose());
      }
      s_.template block<kMeasDim, kMeasDim>(j * kMeasDim, j * kMeasDim) +=
          observations[static_cast<std::size_t>(j)].noise;
    }
    if (!s_factor_.compute(s_)) return {NumericalStatus::kNotPositiveDefinite};

    // Everything else goes through G = S^-1 H_c (3M x kCols) and kCols x kCols reductions of
    // it; the 9 x 3M gain K = P[:, 0:kCols] G^T is never formed:
    //   K nu = P_c (G^T nu),  K H = P_c (H_c^T G),  K R K^T = P_c (sum_i G_i^T R_i G_i) P_c^T.
    s_inv_h_ = h_;
    s_factor_.solve_in_place(s_inv_h_);
    const Matrix<N, kCols> p_c = state.covariance.template leftCols<kCols>();
    const Vector<kCols> g_nu = s_inv_h_.transpose().lazyProduct(innovation_);
    const Covariance<kCols> c_hg = h_.transpose().lazyProduct(s_inv_h_);
    Covariance<kCols> noise_part = Covariance<kCols>::Zero();
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      const Matrix<kMeasDim, kCols> g_i = s_inv_h_.template middleRows<kMeasDim>(row);
      const Matrix<kMeasDim, kCols> r_g = observations[i].noise.lazyProduct(g_i);
      noise_part.noalias() += g_i.transpose().lazyProduct(r_g);
    }

    // Joseph form, (I - KH) P (I - KH)^T + K R K^T. KH and P_c (RG^T) are plain loops in a
    // fixed order: Eigen vectorises fixed-size results of 9 rows with a peel that depends on the
    // object's address, and its scalar and packet paths round differently, so the same inputs
    // could give other bits in another process. joseph_without_noise, shared with the
    // single-sensor update, keeps Eigen's lazy products on local matrices; the integration tests
    // (every state component of every step, DDS center against in-process) show the same bits.
    Matrix<N, kCols> kh;
    Matrix<N, kCols> p_noise;
    SKYFUSE_UNROLL
    for (int r = 0; r < N; ++r) {
      SKYFUSE_UNROLL
      for (int c = 0; c < kCols; ++c) {
        double k_h = 0.0;
        double p_n = 0.0;
        SKYFUSE_UNROLL
        for (int q = 0; q < kCols; ++q) {
          k_h += p_c(r, q) * c_hg(q, c);
          p_n += p_c(r, q) * noise_part(q, c);
        }
        kh(r, c) = k_h;
        p_noise(r, c) = p_n;
      }
    }
    Covariance<N> joseph = joseph_without_noise<N, kCols>(state.covariance, kh);
    // K R K^T = p_noise P_c^T is symmetric: the upper triangle, mirrored.
    for (int c = 0; c < N; ++c) {
      for (int r = 0; r <= c; ++r) {
        double sum = 0.0;
        SKYFUSE_UNROLL
        for (int q = 0; q < kCols; ++q) sum += p_noise(r, q) * p_c(c, q);
        joseph(r, c) += sum;
      }
    }
    for (int c = 0; c < N; ++c) {
      for (int r = c + 1; r < N; ++r) joseph(r, c) = joseph(c, r);
    }
    SKYFUSE_UNROLL
    for (int r = 0; r < N; ++r) {
      double sum = 0.0;
      SKYFUSE_UNROLL
      for (int q = 0; q < kCols; ++q) sum += p_c(r, q) * g_nu(q);
      state.mean(r) += sum;
    }
    state.covariance = joseph;

    // NIS = nu^T S^-1 nu = |L^-1 nu|^2: the forward half of a solve is enough.
    whitened_ = innovation_;
    s_factor_.forward_solve_in_place(whitened_);
    return {NumericalStatus::kOk, whitened_.squaredNorm()};
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
    s_factor_.reserve(m);
  }

  Eigen::Matrix<double, Eigen::Dynamic, kCols, Eigen::RowMajor> h_;
  Eigen::VectorXd innovation_;
  Eigen::VectorXd whitened_;
  Eigen::Matrix<double, Eigen::Dynamic, kCols, Eigen::RowMajor> hp_;  // H_c P_cc
  typename StackedCholesky<kMeasDim, kCols>::RowMajorRhs s_inv_h_;
  Eigen::MatrixXd s_;
  StackedCholesky<kMeasDim, kCols> s_factor_;
};

}  // namespace skyfuse
