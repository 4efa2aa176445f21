#pragma once
// One run of filter kind "ncrkf" stepping through its measurements: the peers' fused NCRKF and
// the center's stacked one (tracking/tdoa_round.hpp), by the same rule the processes will
// follow. Same interface as monte_carlo.cpp's RunStepper. Its members are compiled once, in
// ncrkf_run_stepper.cpp: the class is no template, and every shard of the Monte Carlo includes
// this header.

#include <span>
#include <vector>

#include "sim/run_setup.hpp"
#include "skyfuse/models/state_position.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

class NcrkfRunStepper {
 public:
  using Model = TdoaRelativeMotion;
  static constexpr int kDim = Model::kDim;
  using Sensor = RangeDifferenceSensor<kDim>;
  using Observation = StationObservation<Sensor>;
  using Measurement = Vector<1>;

  /// Refuses a NIS gate: the NCRKF's increments are not an EKF's.
  NcrkfRunStepper(const Scenario& scenario, const TruthTrajectory& truth, int stations,
                  std::uint64_t run, const NisGate& gate);

  void step(std::size_t k, const Vector<kKinematicsDim>& x, std::span<const Measurement> z,
            const StepObserver& observer);

  RunTrace take_trace() { return std::move(trace_); }

 private:
  // Fuses the usable increments of the round onto `tracker`'s prior by the TDOA round rule.
  // Returns how many indefinite increments it refused.
  int fuse(PeerTracker<Model>& tracker, PeerRound<Model>& round, std::size_t k, const char* who);

  Model motion_;
  PeerTracker<Model> central_;
  PeerTracker<Model> peers_;
  std::vector<std::size_t> order_;  // ascending id -> scenario index
  std::vector<Observation> observations_;
  std::vector<InformationIncrement<kDim>> increments_;
  std::vector<bool> usable_;  // each measurement passed its check
  PeerRound<Model> central_round_;
  PeerRound<Model> peer_round_;
  RunTrace trace_;
};

}  // namespace skyfuse
