#pragma once
// What a station fuses when the run's filter is one model (kind ekf): one increment per station
// and round, fused onto the lowest-id contribution's prior (tracking/round_rule.hpp). The
// station process (station_process.cpp) moves the samples; this decides what they mean.
// ImmFusion (imm_fusion.hpp) has the same interface.

#include <fmt/format.h>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::station {

template <typename Sensor>
class SingleModelFusion {
 public:
  using Model = transport::WireModel;
  static constexpr int kDim = Model::kDim;
  using Contribution = PeerContribution<kDim>;

  explicit SingleModelFusion(const RunPlan& plan)
      : tracker_(plan.motion_model<Model>(), plan.initial_estimate<Model>()),
        collector_(plan.participant_ids()),
        round_(collector_.station_ids(), plan.weights_of(collector_.station_ids())) {}

  std::span<const int> station_ids() const { return collector_.station_ids(); }
  void start_at(std::uint64_t step) { collector_.start_at(step); }

  /// Screens this station's own measurement against the common prior, writes its contribution
  /// (write(sample)) and keeps it for the round.
  template <typename Write>
  OwnContribution contribute(std::uint64_t k, const StationObservation<Sensor>& observation,
                             const NisGate& gate, std::uint64_t run_id, Write write) {
    Contribution own;
    own.prior = tracker_.estimate();
    const OwnContribution result = skyfuse::contribute(own.prior, observation, gate, own.increment);
    if (result.status != NumericalStatus::kOk) return result;
    write(transport::to_wire(own, run_id, static_cast<std::uint32_t>(k)));
    collector_.offer(k, observation.station_id, own);
    return result;
  }

  /// Checks a peer's sample (its run id already checked) and keeps it; why not if it did not.
  std::optional<DropKind> admit(const wire::InformationIncrement& sample,
                                const transport::WriterId& writer,
                                transport::SourceBinding& sources) {
    if (!transport::is_single_model_sample(sample)) return DropKind::kOutOfRange;
    const auto contribution = transport::contribution_from_wire<kDim>(sample);
    if (!contribution) return DropKind::kOutOfRange;  // not the run's state dimension
    if (const auto why = check_contribution(*contribution)) return why;
    return transport::admit(collector_, sources, sample.step(), sample.station_id(), writer,
                            *contribution);
  }

  /// Stations whose contribution to the current round is in.
  std::size_t arrived_count() const { return collector_.count(); }

  /// Fuses what arrived; arrived() then says whether anything did.
  RoundFusion fuse() {
    return round_.fuse(tracker_, [&](std::size_t i) {
      if (!collector_.filled(i)) return PeerSlot<kDim>{};
      const Contribution& c = collector_.payloads()[i];
      return PeerSlot<kDim>{&c.increment, &c.prior};
    });
  }
  bool arrived() const { return round_.arrived(); }

  /// The fused track of the round just fused.
  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int station_id) const {
    return transport::to_wire(tracker_.estimate(), run_id, static_cast<std::uint32_t>(k),
                              station_id, wire::PEER, round_.contributors());
  }

  void predict() { tracker_.predict(); }
  void advance() { collector_.advance(); }

 private:
  PeerTracker<Model> tracker_;
  StepCollector<Contribution> collector_;
  PeerRound<Model> round_;
};

}  // namespace skyfuse::station
