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

NetworkImmFilter::CommonState network_imm_start(
    const GaussianState<ConstantAcceleration3D::kDim>& initial, double turn_rate_variance) {
  NetworkImmFilter::CommonState out;
  out.mean.setZero();
  out.mean.head<ConstantAcceleration3D::kDim>() = initial.mean;
  out.covariance.setZero();
  out.covariance.topLeftCorner<ConstantAcceleration3D::kDim, ConstantAcceleration3D::kDim>() =
      initial.covariance;
  out.covariance(KinematicState::kTurnRate, KinematicState::kTurnRate) = turn_rate_variance;
  return out;
}

NetworkImmFilter make_network_imm(const Scenario& scenario,
                                  const GaussianState<ConstantAcceleration3D::kDim>& initial) {
  const ImmConfig& modes = scenario.filter.imm;
  const double dt = scenario.time_step_s;
  const double switch_probability = (1.0 - modes.stay_probability) / 2.0;
  Matrix<3, 3> switching = Matrix<3, 3>::Constant(switch_probability);
  switching.diagonal().setConstant(modes.stay_probability);
  return NetworkImmFilter(
      {ConstantVelocity3D(dt, modes.constant_velocity), network_imm_ca_model(scenario),
       CoordinatedTurn3D(dt, modes.coordinated_turn)},
      switching, Vector3::Constant(1.0 / 3.0),
      network_imm_start(initial, modes.initial_turn_rate_variance));
}

}  // namespace skyfuse
