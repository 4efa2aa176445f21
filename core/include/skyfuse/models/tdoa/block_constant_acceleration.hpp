#pragma once
/// \file
/// Paper 002's motion model (Eq 8, with SEEDS.md's corrections): constant acceleration on
/// kAxes coordinates at once, the state ordered by derivative, [p (kAxes); v (kAxes);
/// a (kAxes)]:
///
///   F = [[I, T I, T^2/2 I], [0, I, T I], [0, 0, I]]   (the paper prints T/2 for T^2/2),
///   Q = q G G^T,  G = [T^2/2 I; T I; I]               (u ~ (0, q I), one draw per step).
///
/// kAxes = 3 is the NCRKF's relative state [dx, dy, d_t1, ...] (the range d_t1 to the
/// reference UAV moves like a third coordinate; d = |dp| is not enforced); kAxes = 2 the EKF's
/// [dx, dy, ...]. The formation's own acceleration (the paper's u^c) is zero here: the UAVs fly
/// at constant velocity.

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/block_kinematics.hpp"
#include "skyfuse/models/linear_transition.hpp"

namespace skyfuse {

template <int kAxes>
class BlockConstantAcceleration : public LinearTransition<3 * kAxes> {
 public:
  static constexpr int kPosition = 0;
  static constexpr int kVelocity = kAxes;
  static constexpr int kAcceleration = 2 * kAxes;

  /// `acceleration_variance`: q, the variance of each acceleration component's increment per
  /// step.
  BlockConstantAcceleration(double time_step_s, double acceleration_variance) {
    constexpr int N = 3 * kAxes;
    const double t = time_step_s;
    const Matrix<kAxes, kAxes> eye = Matrix<kAxes, kAxes>::Identity();
    this->transition_.template block<kAxes, kAxes>(kPosition, kVelocity) = t * eye;
    this->transition_.template block<kAxes, kAxes>(kPosition, kAcceleration) = 0.5 * t * t * eye;
    this->transition_.template block<kAxes, kAxes>(kVelocity, kAcceleration) = t * eye;
    Matrix<N, kAxes> g;
    g << 0.5 * t * t * eye, t * eye, eye;
    this->process_noise_ = acceleration_variance * g * g.transpose();
    time_step_s_ = t;
  }

  /// F P F^T + Q, with F's structure (models/block_kinematics.hpp).
  Covariance<3 * kAxes> propagate_covariance(const Covariance<3 * kAxes>& p) const {
    Covariance<3 * kAxes> out = propagate_block_kinematics<kAxes>(p, time_step_s_);
    out += this->process_noise_;
    return out;
  }

 private:
  double time_step_s_ = 0.0;
};

}  // namespace skyfuse
