#pragma once
/// \file
/// The station network's IMM of 3-D modes, as every process runs it: the peers' fused form
/// (stations), the central stacked form (fusion center) and the in-process twin of both
/// (sim/imm_run_stepper.hpp). Its modes are the scenario's (FilterConfig::imm, one of the sets
/// the registry compiles: tracking/imm_modes.hpp), mixed in [p; v; a; omega]; a CA mode is the
/// scenario's CA filter (its process noise).

#include <type_traits>

#include "skyfuse/core/types.hpp"
#include "skyfuse/models/kinematic_state.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/tracking/imm_modes.hpp"
#include "skyfuse/tracking/imm_network.hpp"

namespace skyfuse {

/// Each mode as the scenario configures it (its noise; the CA mode's is the filter's model).
ConstantVelocity3D make_imm_mode(std::type_identity<ConstantVelocity3D>, const Scenario& scenario);
ConstantAcceleration3D make_imm_mode(std::type_identity<ConstantAcceleration3D>,
                                     const Scenario& scenario);
CoordinatedTurn3D make_imm_mode(std::type_identity<CoordinatedTurn3D>, const Scenario& scenario);

/// `initial` ([p; v; a] and P0) in the IMM's common state: turn rate 0 with variance
/// `turn_rate_variance`, uncorrelated with the rest.
GaussianState<KinematicState::kDim> network_imm_start(
    const GaussianState<ConstantAcceleration3D::kDim>& initial, double turn_rate_variance);

/// The filter types of the network IMM of mode set `Set`.
template <typename Set>
struct NetworkImm;
template <typename... Modes>
struct NetworkImm<ImmModeSet<Modes...>> {
  using Filter = Imm<KinematicState, Modes...>;
  /// As each peer runs it, and as the center does.
  using Peer = PeerImm<KinematicState, Modes...>;
  using Central = CentralImm<KinematicState, Modes...>;
  static constexpr int kModes = sizeof...(Modes);

  /// The IMM of `scenario` (its modes' noise and ImmConfig) starting from `initial` (its
  /// [p; v; a] estimate and P0): every mode equally likely; a mode stays with
  /// stay_probability and leaves for each other mode with an equal share of the rest.
  static Filter make(const Scenario& scenario,
                     const GaussianState<ConstantAcceleration3D::kDim>& initial) {
    const ImmConfig& config = scenario.filter.imm;
    Matrix<kModes, kModes> switching =
        Matrix<kModes, kModes>::Constant((1.0 - config.stay_probability) / (kModes - 1.0));
    switching.diagonal().setConstant(config.stay_probability);
    return Filter({make_imm_mode(std::type_identity<Modes>{}, scenario)...}, switching,
                  Vector<kModes>::Constant(1.0 / kModes),
                  network_imm_start(initial, config.initial_turn_rate_variance));
  }
};

/// The IMM of the default modes (CV, CA, CT), as paper 000's IMM experiment runs it.
using NetworkImmFilter = NetworkImm<DefaultImmModes>::Filter;
using NetworkPeerImm = NetworkImm<DefaultImmModes>::Peer;
using NetworkCentralImm = NetworkImm<DefaultImmModes>::Central;

/// The scenario's CA model (its filter's process noise), an IMM's CA mode. Throws
/// std::invalid_argument when the scenario's filter is not constant_acceleration_3d.
ConstantAcceleration3D network_imm_ca_model(const Scenario& scenario);

}  // namespace skyfuse
