#pragma once
/// \file
/// What every linear motion model has in common: x+ = F x, dF/dx = F wherever it is evaluated,
/// and a constant Q. A linear model derives from this and fills F and Q in its constructor.

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <int N>
class LinearTransition {
 public:
  static constexpr int kDim = N;
  using State = Vector<N>;

  State propagate(const State& x) const { return transition_ * x; }
  /// The model is linear: dF/dx is F wherever it is evaluated.
  const Covariance<N>& jacobian(const State& /*x*/) const { return transition_; }
  const Covariance<N>& process_noise() const { return process_noise_; }

 protected:
  Covariance<N> transition_ = Covariance<N>::Identity();
  Covariance<N> process_noise_ = Covariance<N>::Zero();
};

}  // namespace skyfuse
