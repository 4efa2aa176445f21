#pragma once
/// \file
/// The station network's IMM of 3-D CV, CA and CT modes, as every process runs it: the peers'
/// fused form (stations), the central stacked form (fusion center) and the in-process twin of
/// both (sim/imm_run_stepper.hpp). The IMM's modes are the scenario's (FilterConfig::imm),
/// whatever its filter kind; its CA mode is the scenario's CA filter (its process noise).

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/coordinated_turn_3d.hpp"
#include "skyfuse/models/kinematic_state.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/imm_network.hpp"

namespace skyfuse {

using NetworkImmFilter =
    Imm<KinematicState, ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D>;
/// The network's IMM as each peer and as the center runs it.
using NetworkPeerImm =
    PeerImm<KinematicState, ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D>;
using NetworkCentralImm =
    CentralImm<KinematicState, ConstantVelocity3D, ConstantAcceleration3D, CoordinatedTurn3D>;

/// The IMM of `scenario` (its filter's CA model and ImmConfig) starting from `initial` (its
/// [p; v; a] estimate and P0).
NetworkImmFilter make_network_imm(const Scenario& scenario,
                                  const GaussianState<ConstantAcceleration3D::kDim>& initial);

/// The scenario's CA model (its filter's process noise), the IMM's CA mode. Throws
/// std::invalid_argument when the scenario's filter is not constant_acceleration_3d.
ConstantAcceleration3D network_imm_ca_model(const Scenario& scenario);

/// `initial` ([p; v; a] and P0) in the IMM's common state: turn rate 0 with variance
/// `turn_rate_variance`, uncorrelated with the rest.
NetworkImmFilter::CommonState network_imm_start(
    const GaussianState<ConstantAcceleration3D::kDim>& initial, double turn_rate_variance);

}  // namespace skyfuse
