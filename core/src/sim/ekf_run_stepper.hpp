#pragma once
// One run of filter kind "ekf" stepping through its measurements: the center's stacked EKF and
// the peers' fused increments, by the round rule the station and center processes follow, so
// that this is the in-process twin of a lock-step `skyfuse run`.

#include <fmt/format.h>

#include <span>
#include <vector>

#include "sim/run_setup.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/registry/sensor_pack.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/central_tracker.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

// One station count's pair of trackers stepping through one run. Measurements come from
// outside, indexed like scenario.stations, so that several station counts can share one
// simulation of them: station i's draw does not depend on how many stations run.
template <typename Model, template <int> class SensorOf>
class EkfRunStepper {
 public:
  static constexpr int kDim = Model::kDim;
  // One sensor type, or a SensorPack when the stations' sensors differ.
  using Sensor = SensorOf<kDim>;
  using Observation = ObservationFor<Sensor>;
  /// Room for any station's measurement; a station's own is its first entries.
  using Measurement = Vector<max_measurement_dim<Sensor>()>;
  using Increment = InformationIncrement<kDim>;

  EkfRunStepper(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                std::uint64_t run, const NisGate& gate)
      : motion_(make_motion_model<Model>(scenario)),
        central_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        peers_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
        gate_(gate),
        order_(run_setup::ascending(scenario, stations)),
        observations_(run_setup::checked_observations<Sensor>(scenario, order_, run)),
        peer_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_),
                    round_fanout_for(scenario, static_cast<std::size_t>(stations))),
        central_round_(order_.size()),
        trace_(run_setup::sized_trace(scenario.steps)) {
    // Everything sized once per run: the step loop allocates nothing. Slots are in ascending
    // station id, the order of every round.
    increments_.resize(order_.size());
  }

  // Updates both trackers with step k's measurements (z[i] belongs to scenario.stations[i]) by
  // the round rule, records, then predicts to k + 1.
  void step(std::size_t k, const Vector<kKinematicsDim>& x, std::span<const Measurement> z,
            const StepObserver& observer) {
    for (std::size_t j = 0; j < order_.size(); ++j) {
      with_observation(observations_[j], [&](auto& obs) {
        constexpr int kMeasDim = std::decay_t<decltype(obs.z)>::RowsAtCompileTime;
        obs.z = z[order_[j]].template head<kMeasDim>();
        const OwnContribution own =
            EkfIncrementRule::contribute(peers_.estimate(), obs, gate_, increments_[j]);
        if (own.status != NumericalStatus::kOk) {
          throw NumericalError(fmt::format("p2p: step {}, station {}: increment failed: {}", k,
                                           obs.station_id, to_string(own.status)));
        }
        if (own.refused) ++trace_.refused_p2p;
      });
    }
    const UpdateReport central_report = central_round_.update(
        central_, observations_.size(), [&](std::size_t j) { return &observations_[j]; }, gate_,
        [&](int, DropKind) { ++trace_.refused_central; });
    if (central_report.status != NumericalStatus::kOk) {
      throw NumericalError(fmt::format("central: step {}: stacked update failed: {}", k,
                                       to_string(central_report.status)));
    }
    const RoundFusion fused = peer_round_.fuse(peers_, [&](std::size_t j) {
      return PeerSlot<kDim>{&increments_[j], &peers_.estimate()};
    });
    if (fused.status != NumericalStatus::kOk) {
      throw NumericalError(
          fmt::format("p2p: step {}: fusion failed: {}", k, to_string(fused.status)));
    }

    run_setup::record_step(trace_, k, x, central_.estimate(), peers_, central_report.nis, observer);
    central_.predict();
    peers_.predict();
  }

  RunTrace take_trace() { return std::move(trace_); }

 private:
  Model motion_;
  CentralTracker<Model, Sensor> central_;
  PeerTracker<Model> peers_;
  NisGate gate_;
  std::vector<std::size_t> order_;         // ascending id -> scenario index
  std::vector<Observation> observations_;  // ascending station id
  std::vector<Increment> increments_;      // ascending station id
  PeerRound<Model> peer_round_;
  CentralRound<Model, Sensor> central_round_;
  RunTrace trace_;
};

}  // namespace skyfuse
