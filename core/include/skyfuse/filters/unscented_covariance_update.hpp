#pragma once
/// \file
/// The covariance-form UKF's update on a stacked measurement: the textbook form that the
/// unscented information filter (filters/unscented.hpp) is compared with. Every station's
/// predictions over the prior's sigma points chi_j are stacked into Z_j, and
///
///   z^ = sum Wm_j Z_j,   S = sum Wc_j (Z_j - z^)(Z_j - z^)^T + R,
///   P_xz = sum Wc_j (chi_j - x^)(Z_j - z^)^T,   K = P_xz S^-1,
///   x+ = x^ + K nu,   P+ = P - K S K^T.
///
/// The information form replaces S by H~ P H~^T + R, leaving out the spread of h about its
/// regression on the state, P_zz - H~ P H~^T: zero for a linear sensor, where both forms are the
/// Kalman update; small where h is nearly linear across the sigma points. Not a hot path: it
/// runs beside the information form to say how far apart they lie.

#include <Eigen/Cholesky>
#include <span>
#include <vector>

#include "skyfuse/core/status.hpp"
#include "skyfuse/core/types.hpp"
#include "skyfuse/filters/unscented.hpp"

namespace skyfuse {

/// The covariance-form update of `sigma`'s prior with the stacked observations, into
/// `posterior`; the prior itself when there are none. kNotPositiveDefinite if S is not.
template <int N, typename Observation>
NumericalStatus covariance_form_unscented_update(const SigmaPoints<N>& sigma,
                                                 const GaussianState<N>& prior,
                                                 std::span<const Observation* const> stacked,
                                                 GaussianState<N>& posterior) {
  posterior = prior;
  if (stacked.empty()) return NumericalStatus::kOk;
  using Sensor = decltype(stacked.front()->sensor);
  constexpr int M = Sensor::kMeasDim;
  constexpr int kPoints = SigmaPoints<N>::kCount;
  const auto rows = static_cast<Eigen::Index>(M * stacked.size());

  Eigen::MatrixXd z_points(rows, kPoints);  // column j: Z_j
  Eigen::VectorXd predicted = Eigen::VectorXd::Zero(rows);
  Eigen::VectorXd innovation(rows);
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t i = 0; i < stacked.size(); ++i) {
    const Observation& o = *stacked[i];
    const Eigen::Index row = static_cast<Eigen::Index>(M * i);
    const SigmaPredictions<M, N> predictions = predict_sigma_points(sigma, o.sensor);
    for (int j = 0; j < kPoints; ++j) {
      z_points.block<M, 1>(row, j) = predictions.points[static_cast<std::size_t>(j)];
    }
    const Vector<M>& mean = predictions.mean;
    predicted.segment<M>(row) = mean;
    innovation.segment<M>(row) = Sensor::residual(o.z, mean);
    s.block<M, M>(row, row) = o.noise;
  }
  Eigen::MatrixXd cross = Eigen::MatrixXd::Zero(N, rows);  // P_xz
  for (int j = 0; j < kPoints; ++j) {
    const Eigen::VectorXd spread = z_points.col(j) - predicted;
    s += sigma.covariance_weight(j) * spread * spread.transpose();
    cross += sigma.covariance_weight(j) * (sigma.point(j) - prior.mean) * spread.transpose();
  }
  const Eigen::LLT<Eigen::MatrixXd> s_factor(s);
  if (s_factor.info() != Eigen::Success) return NumericalStatus::kNotPositiveDefinite;
  const Eigen::MatrixXd gain = s_factor.solve(cross.transpose()).transpose();  // K = P_xz S^-1
  posterior.mean = prior.mean + gain * innovation;
  posterior.covariance = prior.covariance - gain * cross.transpose();  // K S K^T = K P_xz^T
  symmetrize(posterior.covariance);
  return NumericalStatus::kOk;
}

}  // namespace skyfuse
