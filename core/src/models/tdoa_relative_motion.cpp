#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"

namespace skyfuse {

TdoaRelativeMotion::TdoaRelativeMotion(double time_step_s, const NoiseStd& noise_std)
    : BlockConstantAcceleration<3>(time_step_s, noise_std[0] * noise_std[0]) {}

TdoaRelativeMotion::State TdoaRelativeMotion::from_kinematics(const Vector<9>& kinematics) {
  const Vector<2> p = kinematics.segment<2>(0);
  const Vector<2> v = kinematics.segment<2>(3);
  const Vector<2> a = kinematics.segment<2>(6);
  const double d = p.norm();
  const double d_rate = p.dot(v) / d;
  State x;
  x << p, d, v, d_rate, a, (v.squaredNorm() + p.dot(a) - d_rate * d_rate) / d;
  return x;
}

TdoaRelativeMotion::State TdoaRelativeMotion::with_derived_range(const State& x) {
  Vector<9> kinematics = Vector<9>::Zero();
  kinematics.segment<2>(0) = x.segment<2>(kPosition);
  kinematics.segment<2>(3) = x.segment<2>(kVelocity);
  kinematics.segment<2>(6) = x.segment<2>(kAcceleration);
  return from_kinematics(kinematics);
}

}  // namespace skyfuse
