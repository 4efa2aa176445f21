#pragma once
// One run of filter kind "ukf" stepping through its measurements: the peers' fused unscented
// increments and the center's unscented filter on the stacked measurement, which is the same
// increments computed from the raw measurements against the center's own prior and fused onto
// it. The in-process twin of a lock-step `skyfuse run` of a ukf scenario.

#include <fmt/format.h>

#include <span>
#include <stdexcept>
#include <vector>

#include "sim/run_setup.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/increment_rules.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

template <typename Model, template <int> class SensorOf>
class UkfRunStepper {
 public:
  static constexpr int kDim = Model::kDim;
  using Sensor = SensorOf<kDim>;  // one sensor kind (the part says so)
  using Observation = StationObservation<Sensor>;
  using Measurement = Vector<Sensor::kMeasDim>;

  UkfRunStepper(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                std::uint64_t run, const NisGate& gate)
      : motion_(make_motion_model<Model>(scenario)),
        central_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        peers_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        order_(run_setup::ascending(scenario, stations)),
        observations_(run_setup::checked_observations<Sensor>(scenario, order_, run)),
        central_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_)),
        peer_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_)),
        trace_(run_setup::sized_trace(scenario.steps)) {
    if (gate.enabled()) {
      throw std::invalid_argument("filter ukf: takes no NIS gate yet");
    }
    increments_.resize(order_.size());
  }

  void step(std::size_t k, const Vector<9>& x, std::span<const Measurement> z,
            const StepObserver& observer) {
    for (std::size_t j = 0; j < order_.size(); ++j) observations_[j].z = z[order_[j]];
    trace_.refused_central += fuse(central_, central_round_, k, "central");
    trace_.refused_p2p += fuse(peers_, peer_round_, k, "p2p");
    // The unscented update has no EKF innovation covariance: no NIS.
    run_setup::record_step(trace_, k, x, central_.estimate(), peers_, 0.0, observer);
    central_.predict();
    peers_.predict();
  }

  RunTrace take_trace() { return std::move(trace_); }

 private:
  // Every participant's increment against `tracker`'s prior, fused onto it by the round rule
  // (a screened-out measurement gives a zero increment, as a station sends). Returns how many
  // were screened out.
  int fuse(PeerTracker<Model>& tracker, PeerRound<Model>& round, std::size_t k, const char* who) {
    int refused = 0;
    if (!sigma_.compute(tracker.estimate(), UnscentedParameters{})) {
      throw NumericalError(
          fmt::format("{} UKF: step {}: prior covariance not positive definite", who, k));
    }
    for (std::size_t j = 0; j < order_.size(); ++j) {
      const OwnContribution own =
          UnscentedIncrementRule::contribute(sigma_, observations_[j], increments_[j]);
      if (own.status != NumericalStatus::kOk) {
        throw NumericalError(fmt::format("{} UKF: step {}, station {}: increment failed: {}", who,
                                         k, observations_[j].station_id, to_string(own.status)));
      }
      if (own.refused) ++refused;
    }
    const RoundFusion fused = round.fuse(tracker, [&](std::size_t j) {
      return PeerSlot<kDim>{&increments_[j], &tracker.estimate()};
    });
    if (fused.status != NumericalStatus::kOk) {
      throw NumericalError(
          fmt::format("{} UKF: step {}: fusion failed: {}", who, k, to_string(fused.status)));
    }
    return refused;
  }

  Model motion_;
  PeerTracker<Model> central_;
  PeerTracker<Model> peers_;
  std::vector<std::size_t> order_;  // ascending id -> scenario index
  std::vector<Observation> observations_;
  std::vector<InformationIncrement<kDim>> increments_;
  SigmaPoints<kDim> sigma_;  // of the prior being updated, made once a round for every station
  PeerRound<Model> central_round_;
  PeerRound<Model> peer_round_;
  RunTrace trace_;
};

}  // namespace skyfuse
