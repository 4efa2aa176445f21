#pragma once
/// \file
/// The stacked-measurement EKF update for stations with different sensors: each observation
/// brings its own measurement dimension, so the stacked H, nu and R are assembled at run time,
///
///   S = H P H^T + R,  K = P H^T S^-1,  x += K nu,  P = (I - K H) P (I - K H)^T + K R K^T,
///
/// with a Cholesky solve for S (never an inverse). Dynamic sizes: buffers keep their size from
/// one step to the next, so a run with a fixed set of stations allocates in its first step
/// only (tests/alloc shows it). A run of one
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
    // Every product writes into a buffer sized above (lazy products: no temporaries), so a run
    // with a fixed set of stations allocates nothing after its first step.
    ph_.resize(N, rows);
    ph_.noalias() = state.covariance.lazyProduct(h_.transpose());  // P H^T
    s_.resize(rows, rows);
    s_.noalias() = h_.lazyProduct(ph_);
    s_ += noise_;
    factor_.compute(s_);
    if (!llt_succeeded(factor_)) return {NumericalStatus::kNotPositiveDefinite};
    // K^T = S^-1 H P (S symmetric); the gain itself is never formed.
    gain_t_ = ph_.transpose();
    factor_.solveInPlace(gain_t_);
    state.mean.noalias() += gain_t_.transpose().lazyProduct(innovation_);
    const Covariance<N> a =
        Covariance<N>::Identity() - Covariance<N>(gain_t_.transpose().lazyProduct(h_));
    kr_.resize(N, rows);
    kr_.noalias() = gain_t_.transpose().lazyProduct(noise_);  // K R
    Covariance<N> p = a * state.covariance * a.transpose();
    p.noalias() += kr_.lazyProduct(gain_t_);  // K R K^T
    symmetrize(p);
    state.covariance = p;
    // NIS = nu^T S^-1 nu = |L^-1 nu|^2: the forward half of a solve.
    whitened_ = innovation_;
    factor_.matrixL().solveInPlace(whitened_);
    return {NumericalStatus::kOk, whitened_.squaredNorm()};
  }

 private:
  Eigen::Matrix<double, Eigen::Dynamic, N> h_;
  Eigen::VectorXd innovation_;
  Eigen::VectorXd whitened_;
  Eigen::MatrixXd noise_;
  Eigen::Matrix<double, N, Eigen::Dynamic> ph_;      // P H^T
  Eigen::MatrixXd s_;                                // H P H^T + R
  Eigen::Matrix<double, Eigen::Dynamic, N> gain_t_;  // K^T = S^-1 H P
  Eigen::Matrix<double, N, Eigen::Dynamic> kr_;      // K R
  // Factorised from the start, of an empty matrix: Eigen 3.4's default LLT leaves its norm and
  // status unset, and moving the owner before its first factorisation (a tracker is moved into
  // its node) would copy those unset values (GCC's -Wmaybe-uninitialized said so).
  Eigen::LLT<Eigen::MatrixXd> factor_{Eigen::MatrixXd()};
};

}  // namespace skyfuse
