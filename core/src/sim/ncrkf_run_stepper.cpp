#include "sim/ncrkf_run_stepper.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/tracking/tdoa_round.hpp"

namespace skyfuse {

NcrkfRunStepper::NcrkfRunStepper(const Scenario& scenario, const TruthTrajectory& truth,
                                 int stations, std::uint64_t run, const NisGate& gate)
    : motion_(make_motion_model<Model>(scenario)),
      central_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
      peers_(motion_, initial_estimate<Model>(scenario, truth.states.front(), run)),
      order_(run_setup::ascending(scenario, stations)),
      observations_(run_setup::checked_observations<Sensor>(scenario, order_, run)),
      // The center sums in the peers' order too, as fusion_center's NcrkfCenter does.
      central_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_),
                     round_fanout_for(scenario, static_cast<std::size_t>(stations))),
      peer_round_(run_setup::ids(scenario, order_), run_setup::weights(scenario, order_),
                  round_fanout_for(scenario, static_cast<std::size_t>(stations))),
      trace_(run_setup::sized_trace(scenario.steps)) {
  if (gate.enabled()) {
    throw std::invalid_argument(
        "filter ncrkf: takes no NIS gate (its increments are not an "
        "EKF's)");
  }
  increments_.resize(order_.size());
  usable_.assign(order_.size(), true);
}

void NcrkfRunStepper::step(std::size_t k, const Vector<kKinematicsDim>& x,
                           std::span<const Measurement> z, const StepObserver& observer) {
  for (std::size_t j = 0; j < order_.size(); ++j) {
    observations_[j].z = z[order_[j]];
    usable_[j] = !Sensor::check_reported(observations_[j].z);
    if (!usable_[j]) ++trace_.refused_p2p;
    increments_[j] = tdoa_contribution(observations_[j]);
  }
  // The center computes the same increments from the same measurements: its stacked NCRKF is
  // their fusion onto its own prior.
  trace_.refused_central += fuse(central_, central_round_, k, "central");
  trace_.refused_p2p += fuse(peers_, peer_round_, k, "p2p");

  // The pseudo-linear update has no EKF innovation: no NIS.
  run_setup::record_step(trace_, k, x, central_.estimate(), peers_, 0.0, observer);
  central_.predict();
  peers_.predict();
}

int NcrkfRunStepper::fuse(PeerTracker<Model>& tracker, PeerRound<Model>& round, std::size_t k,
                          const char* who) {
  const GaussianState<kDim> prior = tracker.estimate();
  int refused = 0;
  const RoundFusion fused = fuse_tdoa_round(
      round, tracker, order_.size(),
      [&](std::size_t j) {
        return usable_[j] ? PeerSlot<kDim>{&increments_[j], &prior} : PeerSlot<kDim>{};
      },
      [&](std::size_t) { ++refused; });
  if (fused.status != NumericalStatus::kOk) {
    throw NumericalError(
        fmt::format("{} NCRKF: step {}: fusion failed: {}", who, k, to_string(fused.status)));
  }
  return refused;
}

}  // namespace skyfuse
