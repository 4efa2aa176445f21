#pragma once
// What a station fuses when the run's filter is the network IMM of `ModeSet` (kind imm): per
// round, one
// sample per mode from each station (its increment against that mode's prior, the likelihood
// terms, the prior's mode probabilities), collected by (station, mode). A station counts as
// arrived when all its modes have; the round is fused by PeerImm::fuse_round in ascending
// station id onto the lowest-id arrival's mode priors (tracking/imm_network.hpp). Same interface
// as SingleModelFusion (single_model_fusion.hpp), the tree exchange's part included: its sums
// hold every mode's (tracking/imm_partial_sum.hpp).

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/network_imm.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/transport/imm_wire.hpp"
#include "skyfuse/transport/source_binding.hpp"
#include "skyfuse/validation/sample_checks.hpp"
#include "station_sensing.hpp"

namespace skyfuse::station {

template <typename ModeSet>
class ImmFusion {
 public:
  using Peers = typename NetworkImm<ModeSet>::Peer;
  using Contribution = typename Peers::Contribution;
  /// What makes this station's contribution (station_sensing.hpp).
  using Sensing = ImmSensing<ModeSet>;
  /// The sum the tree adds and fuses.
  using TreeSum = typename Peers::Sum;
  static constexpr int kModes = Peers::kModes;
  template <int I>
  using ModeSample =
      transport::ImmModeSample<std::tuple_element_t<I, typename Peers::Filter::ModeStates>::kDim,
                               kModes>;

  /// No re-fusion lag for the IMM (load_any_plan refuses one).
  ImmFusion(const RunPlan& plan, std::size_t /*lag*/)
      : peers_(NetworkImm<ModeSet>::make(plan.scenario,
                                         plan.initial_estimate<ConstantAcceleration3D>()),
               sorted_ascending(plan.participant_ids()), plan.scenario.exchange.round_fanout()),
        collectors_(make_collectors(plan.participant_ids(), std::make_index_sequence<kModes>{})),
        weights_(plan.weights_of(station_ids())),
        assembled_(station_ids().size()) {
    arrivals_.reserve(assembled_.size());
    round_weights_.reserve(assembled_.size());
    contributors_.reserve(assembled_.size());
  }
  /// Contributions kept although their round had closed: none, without re-fusion; and so no
  /// settled tracks either.
  std::uint64_t late_used() const { return 0; }
  std::optional<std::uint64_t> settled_round() const { return std::nullopt; }
  std::pair<std::uint64_t, std::uint64_t> settle(NumericalStatus& status) {
    status = NumericalStatus::kOk;
    return {0, 0};
  }
  wire::TrackEstimate settled_track(std::uint64_t, std::uint64_t, int) const {
    throw std::logic_error("filter imm has no settled tracks");
  }

  std::span<const int> station_ids() const { return std::get<0>(collectors_).station_ids(); }
  void start_at(std::uint64_t step) {
    std::apply([&](auto&... c) { (c.start_at(step), ...); }, collectors_);
  }

  /// Screens this station's own measurement, last taken by `sensing`, against the common
  /// mixture prior, writes one sample per mode (write(sample)) and keeps them for the round.
  template <typename Write>
  OwnContribution contribute(std::uint64_t k, const Sensing& sensing, const NisGate& gate,
                             std::uint64_t run_id, Write write) {
    Contribution own;
    const OwnContribution result = sensing.contribute(peers_, gate, own);
    if (result.status != NumericalStatus::kOk) return result;
    const auto step = static_cast<std::uint32_t>(k);
    Peers::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      write(transport::mode_to_wire<I>(own, run_id, step));
      std::get<I>(collectors_)
          .offer(k, sensing.station_id(),
                 ModeSample<I>{std::get<I>(own.modes), own.terms[I], own.prior_probabilities});
    });
    return result;
  }

  /// Checks a peer's sample (its run id already checked) and keeps it under (station, mode);
  /// why not if it did not.
  std::optional<DropKind> admit(const wire::InformationIncrement& sample,
                                const transport::WriterId& writer,
                                transport::SourceBinding& sources) {
    std::optional<DropKind> why = DropKind::kOutOfRange;  // a mode this run does not have
    Peers::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      if (sample.mode() != static_cast<std::uint32_t>(I)) return;
      const auto mode = transport::mode_from_wire<ModeSample<I>::kDim, kModes>(sample);
      if (!mode) return;  // not this mode's state dimension, or not kModes probabilities
      why = check_mode(*mode);
      if (!why) {
        why = transport::admit(std::get<I>(collectors_), sources, sample.step(),
                               sample.station_id(), writer, *mode);
      }
    });
    return why;
  }

  /// Stations all of whose modes are in for the current round.
  std::size_t arrived_count() const {
    std::size_t count = 0;
    for (std::size_t i = 0; i < assembled_.size(); ++i) count += complete(i) ? 1 : 0;
    return count;
  }

  /// Fuses the stations whose every mode arrived; arrived() then says whether any did. A
  /// station's prior mode probabilities are its first mode's sample's. Refuses nothing at
  /// fusion (on_refused is never called): every sample was checked on arrival.
  template <typename OnRefused>
  RoundFusion fuse(OnRefused /*on_refused*/) {
    arrivals_.clear();
    round_weights_.clear();
    contributors_.clear();
    for (std::size_t i = 0; i < assembled_.size(); ++i) {
      if (!complete(i)) continue;
      arrivals_.push_back(&assemble(i));
      round_weights_.push_back(weights_[i]);
      contributors_.push_back(station_ids()[i]);
    }
    return peers_.fuse_round(arrivals_, round_weights_);
  }

  // The tree exchange (tree_exchange.hpp).

  /// `out` := the contribution of `station_id` kept for the current round (this station's own,
  /// once contribute() made it) as a sum of one, unweighted; false if not all its modes are.
  bool own_sum(int station_id, TreeSum& out) {
    const auto index = position_of(station_ids(), station_id);
    if (!index || !complete(*index)) return false;
    out.assign(assemble(*index));
    return true;
  }
  /// Checks a member's contribution to `step` (`one`: a sum of its modes alone, unweighted),
  /// which reached its aggregator, and keeps it mode by mode; why not if it did not.
  std::optional<DropKind> admit_contribution(std::uint64_t step, int station_id, const TreeSum& one,
                                             const transport::WriterId& writer,
                                             transport::SourceBinding& sources) {
    // Every mode checked before any is kept: a contribution is kept whole or not at all.
    std::optional<DropKind> why;
    Peers::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      if (!why) why = check_mode(mode_of<I>(one));
    });
    Peers::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      if (why) return;
      why = transport::admit(std::get<I>(collectors_), sources, step, station_id, writer,
                             mode_of<I>(one));
    });
    return why;
  }
  /// Cluster c's sum of the current round's contributions, every mode's, in ascending id.
  void sum_cluster(std::size_t c, TreeSum& out) {
    out.clear();
    for (const int id : peers_.layout()->members(c)) {
      const auto index = position_of(station_ids(), id);
      if (index && complete(*index)) out.add(weights_[*index], assemble(*index));
    }
  }
  /// Fuses the current round's total; arrived() then says whether it counted anyone. Refuses
  /// nothing (on_refused is never called): every sum was checked on arrival.
  template <typename OnRefused>
  RoundFusion fuse_total(const TreeSum& total, OnRefused /*on_refused*/) {
    contributors_ = total.contributors;
    return peers_.fuse_total(total);
  }

  bool arrived() const { return !contributors_.empty(); }

  /// The fused track of the round just fused: the mixture's [p; v; a] and the probabilities.
  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int station_id) const {
    return transport::imm_track(peers_.filter(), run_id, k, station_id, wire::PEER, contributors_);
  }

  void predict() { peers_.predict(); }
  void advance() {
    std::apply([](auto&... c) { (c.advance(), ...); }, collectors_);
  }

 private:
  template <std::size_t... I>
  static auto make_collectors(const std::vector<int>& ids, std::index_sequence<I...>) {
    return std::tuple<StepCollector<ModeSample<static_cast<int>(I)>>...>(
        StepCollector<ModeSample<static_cast<int>(I)>>(ids)...);
  }
  // What a mode's sample must be, however it came: its contribution, its likelihood terms, and
  // its prior's mode probabilities.
  template <typename Mode>
  static std::optional<DropKind> check_mode(const Mode& mode) {
    std::optional<DropKind> why = check_contribution(mode.contribution);
    if (!why) why = check_likelihood_terms(mode.terms, mode.contribution.increment);
    if (!why) why = check_mode_probabilities(mode.prior_probabilities);
    return why;
  }
  // Mode I of a sum of one station (a member's contribution, unweighted) as its sample.
  template <int I>
  static ModeSample<I> mode_of(const TreeSum& one) {
    return {{std::get<I>(one.sums), std::get<I>(one.references)},
            one.terms[I],
            one.prior_probabilities};
  }
  bool complete(std::size_t i) const {
    return std::apply([&](const auto&... c) { return (c.filled(i) && ...); }, collectors_);
  }
  // Participant i's contribution, rebuilt from its modes' samples (all in: complete(i)).
  const Contribution& assemble(std::size_t i) {
    Contribution& c = assembled_[i];
    c.station_id = station_ids()[i];
    c.prior_probabilities = std::get<0>(collectors_).payloads()[i].prior_probabilities;
    Peers::for_each_mode([&]<int I>(std::integral_constant<int, I>) {
      const ModeSample<I>& sample = std::get<I>(collectors_).payloads()[i];
      std::get<I>(c.modes) = sample.contribution;
      c.terms[I] = sample.terms;
    });
    return c;
  }

  Peers peers_;
  decltype(make_collectors({}, std::make_index_sequence<kModes>{})) collectors_;
  std::vector<double> weights_;          // ascending station id
  std::vector<Contribution> assembled_;  // per station, rebuilt from its modes each round
  std::vector<const Contribution*> arrivals_;
  std::vector<double> round_weights_;
  std::vector<int> contributors_;
};

}  // namespace skyfuse::station
