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
      h_.template middleRows<kMeasDim>(row) = obs.sensor.jacobian(state.mean);
      innovation_.template segment<kMeasDim>(row) =
          obs.sensor.residual(obs.z, obs.sensor.predict(state.mean));
    }

    pht_.noalias() = state.covariance * h_.transpose();
    s_.noalias() = h_ * pht_;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      s_.template block<kMeasDim, kMeasDim>(row, row) += observations[i].noise;
    }

    s_factor_.compute(s_);
    if (s_factor_.info() != Eigen::Success)
      return {NumericalStatus::kNotPositiveDefinite};

    // K^T = S^-1 (P H^T)^T, solved in place.
    gain_t_ = pht_.transpose();
    s_factor_.solveInPlace(gain_t_);
    state.mean.noalias() += gain_t_.transpose() * innovation_;

    Covariance<N> i_minus_kh = Covariance<N>::Identity();
    i_minus_kh.noalias() -= gain_t_.transpose() * h_;
    Covariance<N> joseph;
    joseph.noalias() = i_minus_kh * state.covariance * i_minus_kh.transpose();
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Eigen::Index row = static_cast<Eigen::Index>(i) * kMeasDim;
      const auto k_i = gain_t_.template middleRows<kMeasDim>(row).transpose();
      joseph.noalias() += k_i * observations[i].noise * k_i.transpose();
    }
    state.covariance = joseph;
    symmetrize(state.covariance);

    whitened_ = innovation_;
    s_factor_.solveInPlace(whitened_);
    return {NumericalStatus::kOk, innovation_.dot(whitened_)};
  }

 private:
  void resize(Eigen::Index m) {
    if (h_.rows() == m)
      return;
    h_.resize(m, N);
    innovation_.resize(m);
    whitened_.resize(m);
    pht_.resize(N, m);
    s_.resize(m, m);
    gain_t_.resize(m, N);
    s_factor_ = Eigen::LLT<Eigen::MatrixXd>(m);
  }

  Eigen::Matrix<double, Eigen::Dynamic, N> h_;
  Eigen::VectorXd innovation_;
  Eigen::VectorXd whitened_;
  Eigen::Matrix<double, N, Eigen::Dynamic> pht_;
  Eigen::MatrixXd s_;
  Eigen::Matrix<double, Eigen::Dynamic, N> gain_t_;
  Eigen::LLT<Eigen::MatrixXd> s_factor_;
};

}  // namespace skyfuse
