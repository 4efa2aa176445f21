#pragma once
/// \file
/// The central reference for an IMM over a station network: one EKF update with every
/// station's measurement stacked (z = [z_1; ...], H = [H_1; ...], R = blkdiag(R_i)), reporting
/// nu^T S^-1 nu and log det S of the stacked innovation. Written for clarity with dynamic
/// matrices: it is what the peers' fused likelihood (fused_likelihood.hpp) is checked against.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "skyfuse/core/llt_success.hpp"
#include "skyfuse/filters/kalman.hpp"
#include "skyfuse/fusion/station_observation.hpp"

namespace skyfuse {

/// `Observations`: a random-access range of StationObservation<Sensor>, all of one sensor
/// type. The report's log_likelihood(m) with m = size * kMeasDim is log N(nu; 0, S).
/// On failure `state` is left unchanged.
template <int N, typename Observations>
UpdateReport stacked_update_with_likelihood(GaussianState<N>& state,
                                            const Observations& observations) {
  using Sensor = std::decay_t<decltype(observations[0].sensor)>;
  constexpr int kM = Sensor::kMeasDim;
  const Eigen::Index m = static_cast<Eigen::Index>(observations.size()) * kM;
  Eigen::MatrixXd h(m, N);
  Eigen::VectorXd innovation(m);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(m, m);
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const auto& o = observations[i];
    const Eigen::Index row = static_cast<Eigen::Index>(i) * kM;
    h.middleRows(row, kM) = o.sensor.jacobian(state.mean);
    innovation.segment(row, kM) = o.sensor.residual(o.z, o.sensor.predict(state.mean));
    r.block(row, row, kM, kM) = o.noise;
  }
  const Eigen::MatrixXd pht = state.covariance * h.transpose();
  const Eigen::MatrixXd s = h * pht + r;
  const Eigen::LLT<Eigen::MatrixXd> s_factor(s);
  if (!llt_succeeded(s_factor)) return {NumericalStatus::kNotPositiveDefinite};

  const Eigen::MatrixXd gain = s_factor.solve(pht.transpose()).transpose();
  const Covariance<N> i_kh = Covariance<N>::Identity() - gain * h;
  state.mean += gain * innovation;
  state.covariance = i_kh * state.covariance * i_kh.transpose() + gain * r * gain.transpose();
  symmetrize(state.covariance);

  UpdateReport report{NumericalStatus::kOk, innovation.dot(s_factor.solve(innovation))};
  report.log_det_innovation = 2.0 * s_factor.matrixLLT().diagonal().array().log().sum();
  return report;
}

}  // namespace skyfuse
