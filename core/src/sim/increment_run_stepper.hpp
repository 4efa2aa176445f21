#pragma once
// One run of a filter part with an increment rule (the unscented filter; any new one) stepping
// through its measurements: the peers' fused increments and the center's filter on the stacked
// measurement, which is the same increments computed from the raw measurements against the
// center's own prior and fused onto it. The in-process twin of a lock-step `skyfuse run` of such
// a scenario (the EKF has its own: its center stacks).

#include <fmt/format.h>

#include <span>
#include <stdexcept>
#include <vector>

#include "sim/run_setup.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

template <typename Model, template <int> class SensorOf, typename Rule>
class IncrementRunStepper {
 public:
  static constexpr int kDim = Model::kDim;
  using Sensor = SensorOf<kDim>;  // one sensor kind (the part says so)
  using Observation = StationObservation<Sensor>;
  using Measurement = Vector<Sensor::kMeasDim>;

  IncrementRunStepper(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                      std::uint64_t run, const NisGate& gate)
      : motion_(make_motion_model<Model>(scenario)),
        central_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        peers_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        order_(run_setup::ascending(scenario, stations)),
        observations_(run_setup::checked_observations<Sensor>(scenario, order_, run)),
        central_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_)),
        peer_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_),
                    round_fanout_for(scenario, static_cast<std::size_t>(stations))),
        gate_(gate),
        trace_(run_setup::sized_trace(scenario.steps)) {
    increments_.resize(order_.size());
  }

  void step(std::size_t k, const Vector<kKinematicsDim>& x, std::span<const Measurement> z,
            const StepObserver& observer) {
    for (std::size_t j = 0; j < order_.size(); ++j) observations_[j].z = z[order_[j]];
    trace_.refused_central += fuse(central_, central_round_, k, "central");
    trace_.refused_p2p += fuse(peers_, peer_round_, k, "p2p");
    // No stacked innovation is formed: no NIS.
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
    if (!round_prior_.prepare(tracker.estimate())) {
      throw NumericalError(
          fmt::format("{}: step {}: prior covariance not positive definite", who, k));
    }
    for (std::size_t j = 0; j < order_.size(); ++j) {
      const OwnContribution own = round_prior_.contribute(observations_[j], gate_, increments_[j]);
      if (own.status != NumericalStatus::kOk) {
        throw NumericalError(fmt::format("{}: step {}, station {}: increment failed: {}", who, k,
                                         observations_[j].station_id, to_string(own.status)));
      }
      if (own.refused) ++refused;
    }
    const RoundFusion fused = round.fuse(tracker, [&](std::size_t j) {
      return PeerSlot<kDim>{&increments_[j], &tracker.estimate()};
    });
    if (fused.status != NumericalStatus::kOk) {
      throw NumericalError(
          fmt::format("{}: step {}: fusion failed: {}", who, k, to_string(fused.status)));
    }
    return refused;
  }

  Model motion_;
  PeerTracker<Model> central_;
  PeerTracker<Model> peers_;
  std::vector<std::size_t> order_;  // ascending id -> scenario index
  std::vector<Observation> observations_;
  std::vector<InformationIncrement<kDim>> increments_;
  // The prior being updated, prepared once a round for every station.
  typename Rule::template RoundPrior<kDim> round_prior_;
  PeerRound<Model> central_round_;
  PeerRound<Model> peer_round_;
  NisGate gate_;
  RunTrace trace_;
};

}  // namespace skyfuse
