#include "skyfuse/tracking/network_imm.hpp"

#include <stdexcept>

namespace skyfuse {

ConstantAcceleration3D network_imm_ca_model(const Scenario& scenario) {
  const Eigen::VectorXd& q = scenario.filter.motion_model.process_noise_std;
  if (scenario.filter.motion_model.kind != ConstantAcceleration3D::kKind || q.size() != 3) {
    throw std::invalid_argument(
        "network IMM: the scenario's filter must be constant_acceleration_3d");
  }
  return ConstantAcceleration3D(scenario.time_step_s, {q(0), q(1), q(2)});
}

ConstantVelocity3D make_imm_mode(std::type_identity<ConstantVelocity3D> /*mode*/,
                                 const Scenario& scenario) {
  return ConstantVelocity3D(scenario.time_step_s, scenario.filter.imm.constant_velocity);
}
ConstantAcceleration3D make_imm_mode(std::type_identity<ConstantAcceleration3D> /*mode*/,
                                     const Scenario& scenario) {
  return network_imm_ca_model(scenario);
}
CoordinatedTurn3D make_imm_mode(std::type_identity<CoordinatedTurn3D> /*mode*/,
                                const Scenario& scenario) {
  return CoordinatedTurn3D(scenario.time_step_s, scenario.filter.imm.coordinated_turn);
}

GaussianState<KinematicState::kDim> network_imm_start(
    const GaussianState<ConstantAcceleration3D::kDim>& initial, double turn_rate_variance) {
  GaussianState<KinematicState::kDim> out;
  out.mean.setZero();
  out.mean.head<ConstantAcceleration3D::kDim>() = initial.mean;
  out.covariance.setZero();
  out.covariance.topLeftCorner<ConstantAcceleration3D::kDim, ConstantAcceleration3D::kDim>() =
      initial.covariance;
  out.covariance(KinematicState::kTurnRate, KinematicState::kTurnRate) = turn_rate_variance;
  return out;
}

}  // namespace skyfuse
