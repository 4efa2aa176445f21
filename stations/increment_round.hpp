#pragma once
// What a station's fusion of one increment per station and round shares, whatever makes the
// increments: the rounds with their fixed-lag re-fusion (tracking/fixed_lag_peer.hpp; lag 0:
// the round rule alone) and the wire around them. SingleModelFusion (the EKF's increments) and
// NcrkfFusion (paper 002's bias-compensated ones) derive from it and differ in how an increment
// is made, checked and fused.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/fixed_lag_peer.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/transport/wire_conversion.hpp"
#include "station_sensing.hpp"

namespace skyfuse::station {

template <typename Model>
class IncrementRound {
 public:
  static constexpr int kDim = Model::kDim;
  using Contribution = PeerContribution<kDim>;
  /// What makes this station's increment (station_sensing.hpp).
  using Sensing = IncrementSensing<kDim>;

  IncrementRound(const RunPlan& plan, std::size_t lag)
      : IncrementRound(plan, sorted_ascending(plan.participant_ids()), lag) {}

  std::span<const int> station_ids() const { return chain_.collector().station_ids(); }
  void start_at(std::uint64_t step) { chain_.start_at(step); }
  /// Contributions kept although their round had closed (re-fused), so far.
  std::uint64_t late_used() const { return chain_.late_used(); }
  /// The round whose estimate the last fuse() made final, if a lag holds one.
  std::optional<std::uint64_t> settled_round() const { return chain_.settled_round(); }
  /// The final track of a settled round (settled_round(), or one of settle()'s).
  wire::TrackEstimate settled_track(std::uint64_t run_id, std::uint64_t step,
                                    int station_id) const {
    wire::TrackEstimate track =
        transport::to_wire(chain_.posterior_of(step), run_id, static_cast<std::uint32_t>(step),
                           station_id, wire::PEER, chain_.contributors_of(step));
    track.settled(true);
    return track;
  }

  /// Stations whose contribution to the current round is in.
  std::size_t arrived_count() const { return chain_.collector().count(); }
  /// Whether anything arrived for the last fuse().
  bool arrived() const { return chain_.round().arrived(); }

  /// The fused track of the round just fused.
  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int station_id) const {
    return transport::to_wire(chain_.tracker().estimate(), run_id, static_cast<std::uint32_t>(k),
                              station_id, wire::PEER, chain_.round().contributors());
  }

  void predict() { chain_.predict(); }
  void advance() { chain_.advance(); }

  // The tree exchange (tree_exchange.hpp), which has no lag.

  /// The tree's clusters of this run (none with the flat exchange).
  const std::optional<ClusterLayout>& layout() const { return chain_.round().layout(); }
  /// The sum the tree adds and fuses.
  using TreeSum = PartialSum<kDim>;
  /// `out` := the contribution of `station_id` kept for the current round (this station's own,
  /// once contribute() made it) as a sum of one, unweighted; false if none is kept.
  bool own_sum(int station_id, TreeSum& out) const {
    const auto& collector = chain_.collector();
    const auto index = position_of(collector.station_ids(), station_id);
    if (!index || !collector.filled(*index)) return false;
    const Contribution& own = collector.payloads()[*index];
    out.clear();
    out.sum = own.increment;
    out.contributors.push_back(station_id);
    out.reference = own.prior;
    return true;
  }
  /// Cluster c's sum of the current round's contributions.
  void sum_cluster(std::size_t c, PartialSum<kDim>& out) const {
    chain_.sum_cluster_current(c, out);
  }
  /// Fuses the current round's total; arrived() then says whether it counted anyone. Refuses
  /// nothing (on_refused is never called): every sum was checked on arrival.
  template <typename OnRefused>
  RoundFusion fuse_total(const PartialSum<kDim>& total, OnRefused /*on_refused*/) {
    return chain_.fuse_total_current(total);
  }

 protected:
  /// Writes this station's own contribution (write(sample)) and keeps it for round k.
  template <typename Write>
  void publish(std::uint64_t k, int station_id, const Contribution& own, std::uint64_t run_id,
               Write write) {
    write(transport::to_wire(own, run_id, static_cast<std::uint32_t>(k)));
    chain_.collector().offer(k, station_id, own);
  }

  /// The contribution a peer's sample carries: null if it is not one model's, of this state
  /// dimension.
  static std::optional<Contribution> contribution_of(const wire::InformationIncrement& sample) {
    if (!transport::is_single_model_sample(sample)) return std::nullopt;
    return transport::contribution_from_wire<kDim>(sample);
  }

  /// Checks a peer's sample (its run id already checked) and keeps it, or says why not: whether
  /// it is a contribution of this run's filter and dimension, then `check(contribution)` (the
  /// filter's own check of what it fuses), then its step, its station and its writer.
  template <typename Check>
  std::optional<DropKind> admit_checked(const wire::InformationIncrement& sample,
                                        const transport::WriterId& writer,
                                        transport::SourceBinding& sources, Check check) {
    const auto contribution = contribution_of(sample);
    if (!contribution) return DropKind::kOutOfRange;  // not the run's filter or dimension
    if (const auto why = check(*contribution)) return why;
    return keep(sample.step(), static_cast<int>(sample.station_id()), writer, sources,
                *contribution);
  }

  /// Keeps a checked contribution of `station_id` for `step`, or says why not: its step, its
  /// station, its writer.
  std::optional<DropKind> keep(std::uint64_t step, int station_id,
                               const transport::WriterId& writer, transport::SourceBinding& sources,
                               const Contribution& contribution) {
    const auto why =
        transport::admit(chain_.collector(), sources, step, station_id, writer, contribution);
    if (!why) chain_.kept(step);
    return why;
  }

 protected:
  FixedLagPeer<Model> chain_;

 private:
  IncrementRound(const RunPlan& plan, const std::vector<int>& ascending_ids, std::size_t lag)
      : chain_(plan.motion_model<Model>(), plan.initial_estimate<Model>(), ascending_ids,
               plan.weights_of(ascending_ids), lag, plan.scenario.exchange.round_fanout()) {}
};

}  // namespace skyfuse::station
