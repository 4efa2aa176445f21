#pragma once
/// \file
/// The one rule for a round: which samples of step k enter, in which order, through which gate,
/// and how they become the fused (information) estimate and the stacked one. The station and
/// center processes, the in-process Monte Carlo and the tests all call it, so a run over DDS
/// and its in-process twin compute the same bits, with or without the NIS gate.
///
///  - Screening: a measurement enters only if its source passed check_observation_source where
///    it was admitted (every received sample; a station's own sensor once), its value is one
///    the sensor can report, and it passes the NIS gate against the prior it would update.
///  - A station screens its own measurement against the common prior; screened out, it still
///    contributes a zero increment, which tells its peers not to wait for one.
///  - Peers fuse the contributions that arrived, in ascending station id, onto the prior of the
///    lowest-id one (peer_tracker.hpp says why).
///  - The center screens each measurement that arrived against its own prior and stacks those
///    that pass, in ascending station id.

#include <optional>
#include <span>
#include <vector>

#include "skyfuse/core/indirect_view.hpp"
#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/tracking/central_tracker.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/validation/nis_gate.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

/// Why `observation` may not update `prior`: a value the sensor cannot report, then the gate;
/// nothing if it may. Its source (noise, site) must have passed check_observation_source.
template <int N, typename Sensor>
std::optional<DropKind> screen_observation(const GaussianState<N>& prior,
                                           const StationObservation<Sensor>& observation,
                                           const NisGate& gate) {
  if (const auto why = Sensor::check_reported(observation.z)) return why;
  if (gate.refuses(prior, observation.sensor, observation.z, observation.noise)) {
    return DropKind::kNisGate;
  }
  return std::nullopt;
}

/// What a station's own measurement became.
struct OwnContribution {
  std::optional<DropKind> refused;  ///< screened out: the increment is zero
  NumericalStatus status = NumericalStatus::kOk;
};

/// A station's increment for its own measurement against the common `prior`, into `out`: the
/// increment if the measurement passes screening, a zero increment (with the reason) if not.
template <int N, typename Sensor>
OwnContribution contribute(const GaussianState<N>& prior,
                           const StationObservation<Sensor>& observation, const NisGate& gate,
                           InformationIncrement<N>& out) {
  OwnContribution result;
  result.refused = screen_observation(prior, observation, gate);
  if (result.refused) {
    out.set_zero(observation.station_id);
    return result;
  }
  result.status = compute_increment(observation.station_id, prior, observation.sensor,
                                    observation.z, observation.noise, out);
  return result;
}

/// One slot of a round: a participant's contribution, or nothing if none arrived.
template <int N>
struct PeerSlot {
  const InformationIncrement<N>* increment = nullptr;
  const GaussianState<N>* prior = nullptr;
};

/// The peers' side of a round for a tracker over `Model`. Holds its buffers: no allocation per
/// round.
///
/// With the flat exchange the increments are fused one by one onto the reference. With the tree
/// exchange (a `fanout`) they are summed per cluster (fusion/partial_sum.hpp, the aggregators'
/// sums), the clusters' sums into the round's total, and the total fused: the order a tree run's
/// peers sum in, so that the in-process twin of such a run holds its bits.
template <typename Model>
class PeerRound {
 public:
  static constexpr int kDim = Model::kDim;

  /// `weights[i]` belongs to the i-th participant in ascending station id `ids`. `fanout` 0:
  /// the flat exchange; k >= 1: the tree exchange's clusters of k.
  PeerRound(std::span<const int> ids, std::span<const double> weights, std::size_t fanout = 0)
      : ids_(ids.begin(), ids.end()), weights_(weights.begin(), weights.end()) {
    increments_.reserve(ids_.size());
    round_weights_.reserve(ids_.size());
    contributors_.reserve(ids_.size());
    if (fanout != 0) {
      layout_.emplace(ids_, fanout);
      cluster_.contributors.reserve(fanout);
      total_.contributors.reserve(ids_.size());
    }
  }

  /// Fuses the round into `tracker`: slot_at(i) is the i-th participant's slot (ascending id).
  /// The reference is the lowest-id contribution's prior. Nothing arrived: status kOk, nothing
  /// fused, arrived() false.
  template <typename SlotAt>
  RoundFusion fuse(PeerTracker<Model>& tracker, SlotAt slot_at) {
    if (layout_) return fuse_by_clusters(tracker, slot_at);
    increments_.clear();
    round_weights_.clear();
    contributors_.clear();
    const GaussianState<kDim>* reference = nullptr;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      const PeerSlot<kDim> slot = slot_at(i);
      if (slot.increment == nullptr) continue;
      if (reference == nullptr) reference = slot.prior;
      increments_.push_back(slot.increment);
      round_weights_.push_back(weights_[i]);
      contributors_.push_back(ids_[i]);
    }
    if (reference == nullptr) return {};
    return tracker.fuse_round(*reference, IndirectView<InformationIncrement<kDim>>(increments_),
                              round_weights_);
  }

  /// Fuses a round's total (the sum of its clusters' sums) onto its reference: what a peer of
  /// a tree exchange does with the total its aggregator sends. An empty total fuses nothing.
  RoundFusion fuse_total(PeerTracker<Model>& tracker, const PartialSum<kDim>& total) {
    contributors_.assign(total.contributors.begin(), total.contributors.end());
    if (total.empty()) return {};
    constexpr double kOne = 1.0;  // the weights are inside the sums
    return tracker.fuse_round(total.reference, std::span(&total.sum, 1), std::span(&kOne, 1));
  }

  /// Cluster c's sum of the slots that arrived (slot_at as for fuse()), into `out`: what the
  /// cluster's aggregator publishes. `Sum`: a PartialSum<kDim>, or one that adds more per
  /// station (TdoaPartialSum).
  template <typename SlotAt, typename Sum>
  void sum_cluster(std::size_t c, SlotAt slot_at, Sum& out) const {
    out.clear();
    for (std::size_t i = layout_->first_index(c); i < layout_->end_index(c); ++i) {
      const PeerSlot<kDim> slot = slot_at(i);
      if (slot.increment != nullptr) out.add(ids_[i], weights_[i], *slot.increment, *slot.prior);
    }
  }

  /// The tree exchange's clusters; none with the flat exchange.
  const std::optional<ClusterLayout>& layout() const { return layout_; }
  /// Whether anything arrived in the last fuse().
  bool arrived() const { return !contributors_.empty(); }
  /// The stations fused in the last fuse(), ascending.
  std::span<const int> contributors() const { return contributors_; }

 private:
  template <typename SlotAt>
  RoundFusion fuse_by_clusters(PeerTracker<Model>& tracker, SlotAt slot_at) {
    total_.clear();
    for (std::size_t c = 0; c < layout_->clusters(); ++c) {
      sum_cluster(c, slot_at, cluster_);
      total_.add(cluster_);
    }
    return fuse_total(tracker, total_);
  }

  std::vector<int> ids_;
  std::vector<double> weights_;
  std::vector<const InformationIncrement<kDim>*> increments_;
  std::vector<double> round_weights_;
  std::vector<int> contributors_;
  std::optional<ClusterLayout> layout_;
  PartialSum<kDim> cluster_;  // the tree exchange's sums, kept for their buffers
  PartialSum<kDim> total_;
};

/// The center's side of a round for a tracker over `Model` with stations of `Sensor`. Holds its
/// buffers: no allocation per round.
template <typename Model, typename Sensor>
class CentralRound {
 public:
  using Observation = ObservationFor<Sensor>;

  explicit CentralRound(std::size_t participants) {
    stacked_.reserve(participants);
    contributors_.reserve(participants);
  }

  /// Screens every observation that arrived (observation_at(i): the i-th participant's in
  /// ascending id, or null) against the tracker's prior, stacks those that pass in that order
  /// and updates; on_refused(station_id, kind) hears of each screened out. An empty round
  /// updates nothing and reports kOk with NIS 0.
  template <typename ObservationAt, typename OnRefused>
  UpdateReport update(CentralTracker<Model, Sensor>& tracker, std::size_t participants,
                      ObservationAt observation_at, const NisGate& gate, OnRefused on_refused) {
    stacked_.clear();
    contributors_.clear();
    for (std::size_t i = 0; i < participants; ++i) {
      const Observation* observation = observation_at(i);
      if (observation == nullptr) continue;
      const auto [station_id, why] = with_observation(*observation, [&](const auto& o) {
        return std::pair{o.station_id, screen_observation(tracker.estimate(), o, gate)};
      });
      if (why) {
        on_refused(station_id, *why);
        continue;
      }
      stacked_.push_back(observation);
      contributors_.push_back(station_id);
    }
    if (stacked_.empty()) return {NumericalStatus::kOk, 0.0};
    return tracker.update_stacked(stacked_);
  }

  /// The stations stacked in the last update(), ascending.
  std::span<const int> contributors() const { return contributors_; }

 private:
  std::vector<const Observation*> stacked_;
  std::vector<int> contributors_;
};

}  // namespace skyfuse
