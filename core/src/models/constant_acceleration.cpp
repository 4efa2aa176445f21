#include "skyfuse/models/constant_acceleration.hpp"

#include "skyfuse/models/block_kinematics.hpp"

namespace skyfuse {

ConstantAcceleration3D::ConstantAcceleration3D(double time_step_s, const NoiseStd& noise_std)
    : time_step_s_(time_step_s) {
  const auto [position, velocity, acceleration] = noise_std;
  const double dt = time_step_s;
  const Matrix3 eye = Matrix3::Identity();
  transition_.setIdentity();
  transition_.block<3, 3>(kPosition, kVelocity) = dt * eye;
  transition_.block<3, 3>(kPosition, kAcceleration) = 0.5 * dt * dt * eye;
  transition_.block<3, 3>(kVelocity, kAcceleration) = dt * eye;

  process_noise_.setZero();
  process_noise_.block<3, 3>(kPosition, kPosition) = position * position * eye;
  process_noise_.block<3, 3>(kVelocity, kVelocity) = velocity * velocity * eye;
  process_noise_.block<3, 3>(kAcceleration, kAcceleration) = acceleration * acceleration * eye;
}

ConstantAcceleration3D::State ConstantAcceleration3D::propagate(const State& x) const {
  const double dt = time_step_s_;
  const double half_dt_sq = 0.5 * dt * dt;
  State next;
  next.segment<3>(kPosition) = x.segment<3>(kPosition) + dt * x.segment<3>(kVelocity) +
                               half_dt_sq * x.segment<3>(kAcceleration);
  next.segment<3>(kVelocity) = x.segment<3>(kVelocity) + dt * x.segment<3>(kAcceleration);
  next.segment<3>(kAcceleration) = x.segment<3>(kAcceleration);
  return next;
}

Covariance<9> ConstantAcceleration3D::propagate_covariance(const Covariance<9>& p) const {
  Covariance<9> out = propagate_block_kinematics<3>(p, time_step_s_);
  out.diagonal() += process_noise_.diagonal();  // Q is diagonal: add only what it holds
  return out;
}

}  // namespace skyfuse
