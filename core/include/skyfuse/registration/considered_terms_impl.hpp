#pragma once
/// \file
/// The definition of considered_terms (considered_biases.hpp), included where a picture's code
/// of one state size is compiled (picture/state_size_code.hpp) and by the tests of other sensors.

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/registration/considered_biases.hpp"

namespace skyfuse {

template <int N, typename Sensor>
bool considered_terms(int station_id, const GaussianState<N>& prior, const Sensor& sensor,
                      const Vector<Sensor::kMeasDim>& z, const Covariance<Sensor::kMeasDim>& noise,
                      const Eigen::Ref<const Eigen::MatrixXd>& g_scaled, ConsideredTerms& out) {
  constexpr int M = Sensor::kMeasDim;
  SmallCholesky<M> r_factor;
  if (!r_factor.compute(noise)) return false;
  const Matrix<M, N> h = sensor.jacobian(prior.mean);
  const Vector<M> innovation = sensor.residual(z, sensor.predict(prior.mean));
  const auto d = g_scaled.cols();
  Matrix<M, Eigen::Dynamic> r_inv_g(M, d);
  for (Eigen::Index c = 0; c < d; ++c) r_inv_g.col(c) = r_factor.solve(g_scaled.col(c));
  out.station_id = station_id;
  out.cross = h.transpose().lazyProduct(r_inv_g);
  out.bias = g_scaled.transpose().lazyProduct(r_inv_g);
  out.bias = 0.5 * (out.bias + out.bias.transpose()).eval();
  out.vector = r_inv_g.transpose().lazyProduct(innovation + h * prior.mean);
  return true;
}

}  // namespace skyfuse
