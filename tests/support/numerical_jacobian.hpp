#pragma once
// The numerical twin of a sensor's analytic Jacobian: central differences of h, taken through
// the sensor's own residual so that a step across an angle's cut is measured the short way
// round, as the filter sees it.

#include <algorithm>
#include <cmath>

#include "skyfuse/core/types.hpp"

namespace skyfuse::test {

template <typename Sensor>
Jacobian<Sensor::kMeasDim, Sensor::kStateDim> numerical_jacobian(
    const Sensor& sensor, const Vector<Sensor::kStateDim>& x) {
  constexpr int N = Sensor::kStateDim;
  Jacobian<Sensor::kMeasDim, N> j;
  for (int i = 0; i < N; ++i) {
    const double step = 1e-4 * std::max(1.0, std::abs(x(i)));
    Vector<N> plus = x;
    Vector<N> minus = x;
    plus(i) += step;
    minus(i) -= step;
    j.col(i) = Sensor::residual(sensor.predict(plus), sensor.predict(minus)) / (2.0 * step);
  }
  return j;
}

}  // namespace skyfuse::test
