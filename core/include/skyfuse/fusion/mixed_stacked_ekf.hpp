#pragma once
/// \file
/// The stacked-measurement EKF update for stations with different sensors: each observation
/// brings its own measurement dimension, so the stacked H, nu and R are assembled at run time,
///
///   S = H P H^T + R,  K = P H^T S^-1,  x += K nu,  P = (I - K H) P (I - K H)^T + K R K^T,
///
/// with a Cholesky solve for S (never an inverse). Dynamic sizes: buffers keep their size from
/// one step to the next, so a run with a fixed set of stations allocates once. A run of one
/// sensor kind uses StackedEkf, which exploits the fixed block size.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <variant>

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/registry/sensor_pack.hpp"

namespace skyfuse {

template <int N, typename Pack>
class MixedStackedEkf {
 public:
  /// `Observations`: a random-access range of Pack::Observation (variants).
  template <typename Observations>
  UpdateReport update(GaussianState<N>& state, const Observations& observations) {
    Eigen::Index rows = 0;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      rows +=
          with_observation(observations[i], [](const auto& o) { return Eigen::Index{o.z.size()}; });
    }
    h_.resize(rows, N);
    innovation_.resize(rows);
    noise_.setZero(rows, rows);
    Eigen::Index row = 0;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      with_observation(observations[i], [&](const auto& o) {
        const Eigen::Index m = o.z.size();
        h_.middleRows(row, m) = o.sensor.jacobian(state.mean);
        innovation_.segment(row, m) = o.sensor.residual(o.z, o.sensor.predict(state.mean));
        noise_.block(row, row, m, m) = o.noise;
        row += m;
      });
    }
    const Eigen::MatrixXd ph = state.covariance * h_.transpose();  // P H^T
    s_ = h_ * ph + noise_;
    factor_.compute(s_);
    if (!llt_succeeded(factor_)) return {NumericalStatus::kNotPositiveDefinite};
    // K = P H^T S^-1 = (S^-1 H P)^T, S symmetric.
    const Eigen::MatrixXd gain = factor_.solve(ph.transpose()).transpose();
    state.mean += gain * innovation_;
    const Covariance<N> a = Covariance<N>::Identity() - gain * h_;
    Covariance<N> p = a * state.covariance * a.transpose() + gain * noise_ * gain.transpose();
    symmetrize(p);
    state.covariance = p;
    return {NumericalStatus::kOk, innovation_.dot(factor_.solve(innovation_))};
  }

 private:
  Eigen::Matrix<double, Eigen::Dynamic, N> h_;
  Eigen::VectorXd innovation_;
  Eigen::MatrixXd noise_;
  Eigen::MatrixXd s_;
  Eigen::LLT<Eigen::MatrixXd> factor_;
};

}  // namespace skyfuse
