#pragma once
/// \file
/// A linear sensor that measures the target position directly (z = [I3 0] x + noise), as a GPS
/// fix does. It is the linear-Gaussian reference case on which filter consistency is tested.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <int StateDim>
class PositionSensor {
 public:
  static constexpr int kStateDim = StateDim;
  static constexpr int kMeasDim = 3;
  static constexpr int kJacobianCols = 3;
  using State = Vector<StateDim>;
  using Measurement = Vector<3>;

  Measurement predict(const State& x) const { return x.template head<3>(); }
  Jacobian<3, StateDim> jacobian(const State& /*x*/) const {
    Jacobian<3, StateDim> h = Jacobian<3, StateDim>::Zero();
    h.template leftCols<3>().setIdentity();
    return h;
  }
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    return z - z_pred;
  }
};

}  // namespace skyfuse
