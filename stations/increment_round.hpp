#pragma once
// What a station's fusion of one increment per station and round shares, whatever makes the
// increments: the tracker over `Model`, the collector of the round's contributions by station,
// and the round rule that fuses them onto the lowest-id contribution's prior
// (tracking/round_rule.hpp). SingleModelFusion (the EKF's increments) and NcrkfFusion (paper
// 002's bias-compensated ones) derive from it and differ in how an increment is made, checked
// and fused.

#include <cstdint>
#include <optional>
#include <span>

#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::station {

template <typename Model>
class IncrementRound {
 public:
  static constexpr int kDim = Model::kDim;
  using Contribution = PeerContribution<kDim>;

  explicit IncrementRound(const RunPlan& plan)
      : tracker_(plan.motion_model<Model>(), plan.initial_estimate<Model>()),
        collector_(plan.participant_ids()),
        round_(collector_.station_ids(), plan.weights_of(collector_.station_ids())) {}

  std::span<const int> station_ids() const { return collector_.station_ids(); }
  void start_at(std::uint64_t step) { collector_.start_at(step); }

  /// Stations whose contribution to the current round is in.
  std::size_t arrived_count() const { return collector_.count(); }
  /// Whether anything arrived for the last fuse().
  bool arrived() const { return round_.arrived(); }

  /// The fused track of the round just fused.
  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int station_id) const {
    return transport::to_wire(tracker_.estimate(), run_id, static_cast<std::uint32_t>(k),
                              station_id, wire::PEER, round_.contributors());
  }

  void predict() { tracker_.predict(); }
  void advance() { collector_.advance(); }

 protected:
  /// Writes this station's own contribution (write(sample)) and keeps it for round k.
  template <typename Write>
  void publish(std::uint64_t k, int station_id, const Contribution& own, std::uint64_t run_id,
               Write write) {
    write(transport::to_wire(own, run_id, static_cast<std::uint32_t>(k)));
    collector_.offer(k, station_id, own);
  }

  /// The contribution a peer's sample carries: null if it is not one model's, of this state
  /// dimension.
  static std::optional<Contribution> contribution_of(const wire::InformationIncrement& sample) {
    if (!transport::is_single_model_sample(sample)) return std::nullopt;
    return transport::contribution_from_wire<kDim>(sample);
  }

  /// Keeps a checked contribution, or says why not: its step, its station, its writer.
  std::optional<DropKind> keep(const wire::InformationIncrement& sample,
                               const transport::WriterId& writer, transport::SourceBinding& sources,
                               const Contribution& contribution) {
    return transport::admit(collector_, sources, sample.step(), sample.station_id(), writer,
                            contribution);
  }

  /// The i-th participant's slot of the current round (ascending id).
  PeerSlot<kDim> slot(std::size_t i) const {
    if (!collector_.filled(i)) return {};
    const Contribution& c = collector_.payloads()[i];
    return {&c.increment, &c.prior};
  }

  PeerTracker<Model> tracker_;
  StepCollector<Contribution> collector_;
  PeerRound<Model> round_;
};

}  // namespace skyfuse::station
