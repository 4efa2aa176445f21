#pragma once
/// \file
/// The definitions of relinearised_point and relinearised_prior (relinearised_increment.hpp),
/// included where a picture's code of one state size is compiled (picture/state_size_code.hpp)
/// and by the tests of other sensors.

#include "skyfuse/core/small_cholesky.hpp"
#include "skyfuse/fusion/relinearised_increment.hpp"

namespace skyfuse {

template <int N, typename Sensor>
Vector<N> relinearised_point(const GaussianState<N>& prior, const StationObservation<Sensor>& o,
                             int times) {
  static_assert(Sensor::kStateDim == N, "sensor and state dimensions differ");
  constexpr int M = Sensor::kMeasDim;
  Vector<N> point = prior.mean;
  for (int i = 0; i < times; ++i) {
    const Matrix<M, N> h = o.sensor.jacobian(point);
    const Matrix<N, M> gain_numerator = prior.covariance * h.transpose();  // P Hᵀ
    SmallCholesky<M> innovation_factor;
    if (!innovation_factor.compute(Covariance<M>(h * gain_numerator + o.noise))) break;
    const Vector<M> innovation =
        o.sensor.residual(o.z, o.sensor.predict(point)) - h * (prior.mean - point);
    point = prior.mean + gain_numerator * innovation_factor.solve(innovation);
  }
  return point;
}

template <int N, typename Sensor>
GaussianState<N> relinearised_prior(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& o, int times) {
  GaussianState<N> at = prior;
  if (times > 0) at.mean = relinearised_point(prior, o, times);
  return at;
}

}  // namespace skyfuse
