#include "skyfuse/models/constant_acceleration.hpp"

namespace skyfuse {

ConstantAcceleration3D::ConstantAcceleration3D(double time_step_s, const ProcessNoiseStd& noise)
    : time_step_s_(time_step_s) {
  const double dt = time_step_s;
  const Matrix3 eye = Matrix3::Identity();
  transition_.setIdentity();
  transition_.block<3, 3>(kPosition, kVelocity) = dt * eye;
  transition_.block<3, 3>(kPosition, kAcceleration) = 0.5 * dt * dt * eye;
  transition_.block<3, 3>(kVelocity, kAcceleration) = dt * eye;

  process_noise_.setZero();
  process_noise_.block<3, 3>(kPosition, kPosition) = noise.position * noise.position * eye;
  process_noise_.block<3, 3>(kVelocity, kVelocity) = noise.velocity * noise.velocity * eye;
  process_noise_.block<3, 3>(kAcceleration, kAcceleration) =
      noise.acceleration * noise.acceleration * eye;
}

}  // namespace skyfuse
