#pragma once
/// \file
/// A sensor that measures a planar model's position, z = [x, y] + noise (paper 001, eq 11):
/// one sensor type per model, since each model keeps x and y at its own indices.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <typename Model>
class Position2D {
 public:
  static constexpr int kStateDim = Model::kDim;
  static constexpr int kMeasDim = 2;
  using State = Vector<kStateDim>;
  using Measurement = Vector<2>;

  static Measurement predict(const State& x) { return {x(Model::kX), x(Model::kY)}; }
  static Jacobian<2, kStateDim> jacobian(const State& /*x*/) {
    Jacobian<2, kStateDim> h = Jacobian<2, kStateDim>::Zero();
    h(0, Model::kX) = 1.0;
    h(1, Model::kY) = 1.0;
    return h;
  }
  static Measurement residual(const Measurement& z, const Measurement& z_pred) {
    return z - z_pred;
  }
};

}  // namespace skyfuse
