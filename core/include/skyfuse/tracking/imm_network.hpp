#pragma once
/// \file
/// An IMM run by a network of stations, two ways that must agree:
///
///  - PeerImm: every peer holds the same IMM. After the common predict (mixing included, the
///    same bits everywhere) each station turns its measurement into one contribution: per
///    mode, its information increment against that mode's prior and the two scalars the mode
///    likelihood needs (fused_likelihood.hpp). Every peer fuses all contributions mode by mode
///    in ascending station id and so computes the same posteriors and mode probabilities.
///  - CentralImm: one IMM whose modes each take the stacked EKF update of all measurements,
///    weighing the modes by the stacked likelihood.
///
/// In exact arithmetic the two are the same filter; tests hold them within 1e-9.
///
/// The round rule (round_rule.hpp) carries over: a measurement is screened against the prior
/// it would update, here the mixture of the modes' priors, and a station whose own measurement
/// is screened out still contributes zero increments and zero likelihood terms, which change
/// neither a mode's state nor its probability. Each contribution carries the mode priors and
/// probabilities it was computed against, and a round is fused onto the lowest-id
/// contribution's, so that peers which lost different contributions hold the same bits again
/// after the next complete round (peer_tracker.hpp says why).
///
/// The rounds (contribute, fuse_round, fuse_total, the center's stacked update) are defined in
/// imm_network_impl.hpp and compiled once per configuration group in core: a file that only runs
/// them links them.

#include <array>
#include <optional>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "skyfuse/core/indirect_view.hpp"
#include "skyfuse/filters/imm.hpp"
#include "skyfuse/fusion/fused_likelihood.hpp"
#include "skyfuse/fusion/information_increment.hpp"
#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/fusion/stacked_likelihood.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"
#include "skyfuse/tracking/imm_partial_sum.hpp"
#include "skyfuse/tracking/peer_contribution.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// The same sensor (same site) for a model of another state dimension. Every mode keeps the
/// position first, which is all a station's sensor reads.
template <int M, template <int> class SensorT, int N>
SensorT<M> sensor_for_dimension(const SensorT<N>& sensor) {
  if constexpr (std::is_constructible_v<SensorT<M>, const SensorT<N>&>) {
    return SensorT<M>(sensor);  // a sensor with more than a site converts itself
  } else if constexpr (SensorT<N>::kNeedsSite) {
    return SensorT<M>(sensor.site());
  } else {
    return SensorT<M>{};
  }
}

/// Why `observation` may not update an IMM whose mixture prior is `mixture()`: a value the
/// sensor cannot report, then the gate against the mixture (computed only with a gate).
template <typename Common, template <int> class SensorT, int N, typename Mixture>
std::optional<DropKind> screen_for_imm(const StationObservation<SensorT<N>>& observation,
                                       const NisGate& gate, Mixture mixture) {
  if (!gate.enabled()) return SensorT<N>::check_reported(observation.z);
  const StationObservation<SensorT<Common::kDim>> in_common{
      observation.station_id, sensor_for_dimension<Common::kDim>(observation.sensor), observation.z,
      observation.noise};
  return screen_observation(mixture(), in_common, gate);
}

template <typename Common, typename... Modes>
class PeerImm {
 public:
  using Filter = Imm<Common, Modes...>;
  using Contribution = ImmContribution<Modes...>;
  using Sum = ImmPartialSum<Modes...>;
  static constexpr int kModes = sizeof...(Modes);

  /// `ids` (ascending) and `fanout` >= 1: the tree exchange's clusters, whose order of
  /// summation fuse_round() then follows; none: the flat exchange.
  explicit PeerImm(Filter imm, std::span<const int> ids = {}, std::size_t fanout = 0)
      : imm_(std::move(imm)) {
    if (fanout != 0) layout_.emplace(ids, fanout);
  }

  /// fn(std::integral_constant<int, I>{}) for every mode I, in order.
  template <typename Fn>
  static void for_each_mode(Fn&& fn) {
    Sum::for_each_mode(std::forward<Fn>(fn));
  }

  /// Mixing and every mode's time update.
  void predict() { imm_.predict(); }

  /// Takes `states` and `probabilities` as its own: a peer taking another's whole picture after
  /// they parted (pictures of many aircraft over DDS). `probabilities` must sum to 1.
  void restore(const typename Filter::ModeStates& states, const Vector<kModes>& probabilities) {
    imm_.restore(states, probabilities);
  }

  /// This station's contribution for `observation` against the current (common) mode priors,
  /// screened as the round rule says (the file comment): screened out, its increments and terms
  /// are zero.
  template <template <int> class SensorT, int N>
  OwnContribution contribute(const StationObservation<SensorT<N>>& observation, const NisGate& gate,
                             Contribution& out) const;

  /// Fuses one round, `contributions` in ascending station id (weights[i] for the i-th), onto
  /// the mode priors and probabilities of the first, which this peer takes as its own if they
  /// differ. On failure nothing changes and nothing counts as resynchronised. An empty round
  /// fuses nothing. With the tree's clusters, the round is summed as the tree sums it
  /// (fusion/partial_sum.hpp): each cluster's contributions from zero, the clusters' sums in
  /// cluster order, the total fused by fuse_total().
  RoundFusion fuse_round(std::span<const Contribution* const> contributions,
                         std::span<const double> weights);

  /// Fuses a round's total (the tree exchange's) onto its reference, as fuse_round() does a
  /// round: every mode's summed increment and terms with weight 1, which changes no bit of
  /// them. An empty total fuses nothing.
  RoundFusion fuse_total(const Sum& total);

  /// The tree exchange's clusters, if this peer sums by them.
  const std::optional<ClusterLayout>& layout() const { return layout_; }

  const Filter& filter() const { return imm_; }

 private:
  // Takes `priors` and `probabilities` as this peer's own if they differ from them, then every
  // mode's update by fuse_mode(mode, state, measurement_dim) -> UpdateReport; on failure the
  // peer is as before.
  template <typename FuseMode>
  RoundFusion fuse_onto(const typename Filter::ModeStates& priors,
                        const Vector<kModes>& probabilities, FuseMode fuse_mode);

  Filter imm_;
  std::optional<ClusterLayout> layout_;
  Sum cluster_;  // fuse_round()'s sums in the tree's order, kept to reuse their storage
  Sum total_;
};

template <typename Common, typename... Modes>
class CentralImm {
 public:
  using Filter = Imm<Common, Modes...>;

  explicit CentralImm(Filter imm) : imm_(std::move(imm)) {}

  void predict() { imm_.predict(); }

  /// Screens each observation (`observation_at(i)`: the i-th of `count` in ascending station
  /// id, or null if none arrived) against the mixture prior, as the peers screen their own, and
  /// gives every mode the stacked update of those that pass; on_refused(station_id, why) hears
  /// of the others, and `contributors` gets the ids stacked. When none passes nothing is
  /// updated: the mode probabilities stay the predicted ones.
  template <typename Observation, typename ObservationAt, typename OnRefused>
  NumericalStatus update(std::size_t count, ObservationAt observation_at, const NisGate& gate,
                         OnRefused on_refused, std::vector<int>& contributors) {
    std::vector<Observation> stacked;
    stacked.reserve(count);
    contributors.clear();
    std::optional<typename Filter::CommonState> mixture;
    for (std::size_t i = 0; i < count; ++i) {
      const Observation* o = observation_at(i);
      if (o == nullptr) continue;
      const auto why = screen_for_imm<Common>(*o, gate, [&] {
        if (!mixture) mixture = imm_.estimate();
        return *mixture;
      });
      if (why) {
        on_refused(o->station_id, *why);
        continue;
      }
      stacked.push_back(*o);
      contributors.push_back(o->station_id);
    }
    if (stacked.empty()) return NumericalStatus::kOk;
    return update(std::span<const Observation>(stacked));
  }

  /// Every mode takes the stacked update of `observations` (ascending station id).
  template <template <int> class SensorT, int N>
  NumericalStatus update(std::span<const StationObservation<SensorT<N>>> observations);

  /// Takes `states` and `probabilities` as its own: the height bound of a picture's 2-D radars
  /// (picture/height_bound.hpp), as a peer's. `probabilities` must sum to 1.
  void restore(const typename Filter::ModeStates& states,
               const Vector<Filter::kModes>& probabilities) {
    imm_.restore(states, probabilities);
  }
  const Filter& filter() const { return imm_; }
  /// Each mode's NIS of the stacked measurement in the last update (against its own prior).
  const Vector<Filter::kModes>& mode_nis() const { return mode_nis_; }

 private:
  Filter imm_;
  Vector<Filter::kModes> mode_nis_ = Vector<Filter::kModes>::Zero();
};

}  // namespace skyfuse
