#pragma once
// One run of filter kind "imm" (its modes `ModeSet`) stepping through its measurements: the central
// stacked IMM and the peers' fused one (tracking/imm_network.hpp), by the same round rule the
// station and center processes follow, so that this is the in-process twin of a lock-step `skyfuse
// run` of an IMM scenario. Same interface as monte_carlo.cpp's RunStepper.
//
// What it records of the IMM: the mixture's [p; v; a] (the turn rate stays inside the modes);
// the NEES of [p; v] only (ImmFilterPart::kNeesDof), since the acceleration is a state of the CA
// mode alone and the mixture's spread in it says nothing of the CT mode's centripetal acceleration;
// and as the central NIS the modes' NIS of the stacked measurement weighed by the prior mode
// probabilities.

#include <fmt/format.h>

#include <span>
#include <vector>

#include "sim/run_setup.hpp"
#include "skyfuse/filters/parts/imm_part.hpp"
#include "skyfuse/metrics/nees.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

template <typename ModeSet, template <int> class SensorOf>
class ImmRunStepper {
 public:
  using Peers = typename NetworkImm<ModeSet>::Peer;
  using Central = typename NetworkImm<ModeSet>::Central;
  /// The stations' sensor at the CA mode's dimension; each mode reads it at its own.
  using Sensor = SensorOf<ConstantAcceleration3D::kDim>;
  using Observation = StationObservation<Sensor>;
  using Measurement = Vector<Sensor::kMeasDim>;
  /// Degrees of freedom of its NEES: [p; v], what every mode shares.
  static constexpr int kNeesDof = ImmFilterPart<ModeSet>::kNeesDof;

  ImmRunStepper(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                std::uint64_t run, const NisGate& gate)
      : central_(NetworkImm<ModeSet>::make(scenario, start(scenario, truth, run))),
        peers_(NetworkImm<ModeSet>::make(scenario, start(scenario, truth, run)),
               run_setup::ids(scenario, run_setup::ascending(scenario, stations)),
               round_fanout_for(scenario, static_cast<std::size_t>(stations))),
        gate_(gate),
        order_(run_setup::ascending(scenario, stations)),
        weights_(run_setup::weights(scenario, order_)),
        observations_(run_setup::checked_observations<Sensor>(scenario, order_, run)),
        trace_(run_setup::sized_trace(scenario.steps)) {
    contributions_.resize(order_.size());
    for (auto& c : contributions_) contribution_order_.push_back(&c);
  }

  void step(std::size_t k, const Vector<kKinematicsDim>& x, std::span<const Measurement> z,
            const StepObserver& observer) {
    for (std::size_t j = 0; j < order_.size(); ++j) {
      observations_[j].z = z[order_[j]];
      const OwnContribution own = peers_.contribute(observations_[j], gate_, contributions_[j]);
      if (own.status != NumericalStatus::kOk) {
        throw NumericalError(fmt::format("p2p IMM: step {}, station {}: increment failed: {}", k,
                                         observations_[j].station_id, to_string(own.status)));
      }
      if (own.refused) ++trace_.refused_p2p;
    }
    const auto prior_probabilities = central_.filter().mode_probabilities();
    const NumericalStatus central = central_.template update<Observation>(
        observations_.size(), [&](std::size_t j) { return &observations_[j]; }, gate_,
        [&](int, DropKind) { ++trace_.refused_central; }, contributors_);
    if (central != NumericalStatus::kOk) {
      throw NumericalError(
          fmt::format("central IMM: step {}: stacked update failed: {}", k, to_string(central)));
    }
    const RoundFusion fused = peers_.fuse_round(contribution_order_, weights_);
    if (fused.status != NumericalStatus::kOk) {
      throw NumericalError(
          fmt::format("p2p IMM: step {}: fusion failed: {}", k, to_string(fused.status)));
    }

    central_estimate_ = kinematics(central_.filter().estimate());
    p2p_estimate_ = kinematics(peers_.filter().estimate());
    const Vector3 p = x.head<3>();
    const Vector3 p_central = central_estimate_.mean.head<3>();
    const Vector3 p_p2p = p2p_estimate_.mean.head<3>();
    run_setup::record_positions(trace_, k, p, p_central, p_p2p);
    trace_.nees_p2p[k] = nees<kNeesDof>(
        x.head<kNeesDof>(), {p2p_estimate_.mean.head<kNeesDof>(),
                             p2p_estimate_.covariance.topLeftCorner<kNeesDof, kNeesDof>()});
    trace_.nis_central[k] =
        contributors_.empty() ? 0.0 : prior_probabilities.dot(central_.mode_nis());
    if (observer) {
      observer({static_cast<int>(k), x, EstimateView::of(central_estimate_),
                EstimateView::of(p2p_estimate_), trace_.nis_central[k], p_central, p_p2p});
    }
    central_.predict();
    peers_.predict();
  }

  RunTrace take_trace() { return std::move(trace_); }

 private:
  static GaussianState<kKinematicsDim> start(const Scenario& scenario, const TruthTrajectory& truth,
                                             std::uint64_t run) {
    return initial_estimate<ConstantAcceleration3D>(scenario, truth.states.front(), run);
  }
  // [p; v; a] of the mixture.
  static GaussianState<kKinematicsDim> kinematics(
      const GaussianState<KinematicState::kDim>& mixture) {
    return {mixture.mean.head<kKinematicsDim>(),
            mixture.covariance.topLeftCorner<kKinematicsDim, kKinematicsDim>()};
  }

  Central central_;
  Peers peers_;
  NisGate gate_;
  std::vector<std::size_t> order_;  // ascending id -> scenario index
  std::vector<double> weights_;     // ascending station id
  std::vector<Observation> observations_;
  std::vector<typename Peers::Contribution> contributions_;
  std::vector<const typename Peers::Contribution*> contribution_order_;
  std::vector<int> contributors_;
  GaussianState<kKinematicsDim> central_estimate_;
  GaussianState<kKinematicsDim> p2p_estimate_;
  RunTrace trace_;
};

}  // namespace skyfuse
