#pragma once
/// \file
/// The fusion center's rounds with fixed-lag re-fusion (`--refusion-lag L`): the collector of
/// each round's measurements by station (which keeps late ones for the L rounds closed last)
/// and each round's prior in the lag. A measurement kept for a closed round b sends the center
/// back to b's prior, and rounds b .. c are updated again with every measurement now held: a
/// late measurement enters the track where it belongs and gives the bits it would have given
/// in time. Without late measurements a round costs one update, whatever L.
///
/// `Fusion` is the stacked update of the run's filter part (what fusion_center/ runs):
///   NumericalStatus update(count, observation_at, gate, on_refused);  void predict();
///   static constexpr bool kRefuses;  and, when kRefuses: state() and reset_to(state).
/// A fusion that takes no lag (its part refuses one) keeps no priors. The peers' counterpart,
/// with its reference priors, is FixedLagPeer (fixed_lag_peer.hpp).

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "skyfuse/core/status.hpp"
#include "skyfuse/tracking/step_collector.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

template <typename Fusion, typename Observation>
class FixedLagCenter {
 public:
  /// `ids` the participants, ascending. A lag for a fusion that takes none is refused earlier
  /// (the loader names the part's refusal); here it is a programming error.
  FixedLagCenter(Fusion fusion, std::span<const int> ids, std::size_t lag)
      : fusion_(std::move(fusion)), collector_(ids, lag) {
    if constexpr (Fusion::kRefuses) {
      priors_.assign(lag + 1, fusion_.state());
    } else if (lag != 0) {
      throw std::logic_error("FixedLagCenter: this fusion takes no re-fusion lag");
    }
  }

  Fusion& fusion() { return fusion_; }
  const Fusion& fusion() const { return fusion_; }
  StepCollector<Observation>& collector() { return collector_; }
  const StepCollector<Observation>& collector() const { return collector_; }
  std::size_t lag() const { return collector_.lag(); }

  /// Tells the chain a measurement for `step` was kept: one for a closed round is late, and
  /// that round is updated again when the current one closes.
  void kept(std::uint64_t step) {
    if (step >= collector_.current_step()) return;
    ++late_used_;
    late_from_ = std::min(late_from_.value_or(step), step);
  }
  /// Measurements kept although their round had closed, so far.
  std::uint64_t late_used() const { return late_used_; }

  /// Updates the current round with what has arrived, by the fusion's round rule; first, from
  /// the earliest round a late measurement came for, the rounds before it again.
  /// on_updated(step) after each round's update (the fusion holds that round's posterior);
  /// on_refused(station_id, why) for the current round's screened-out measurements only, so
  /// each is counted once, when its round closes.
  template <typename OnRefused, typename OnUpdated>
  NumericalStatus close_round(const NisGate& gate, OnRefused on_refused, OnUpdated on_updated) {
    const std::uint64_t k = collector_.current_step();
    std::uint64_t from = k;
    if constexpr (Fusion::kRefuses) {
      if (late_from_) {
        from = *late_from_;
        fusion_.reset_to(prior_of(from));
        late_from_.reset();
      }
    }
    return update_rounds(from, k, gate, on_refused, on_updated);
  }

  /// After close_round(): the round whose estimate is final now, the oldest in the lag.
  std::optional<std::uint64_t> settled_round() const {
    const std::uint64_t k = collector_.current_step();
    if (lag() == 0 || k < lag()) return std::nullopt;
    return k - lag();
  }

  /// Predicts to the next round and opens it.
  void advance() {
    fusion_.predict();
    if constexpr (Fusion::kRefuses) {
      if (lag() != 0) prior_of(collector_.current_step() + 1) = fusion_.state();
    }
    collector_.advance();
  }

  /// The end of the run, after the last round's advance(): the rounds late measurements came
  /// for since are updated again (on_updated as above; no refusal is told twice). Returns the
  /// rounds still in the lag, final now: [from, end).
  template <typename OnUpdated>
  std::pair<std::uint64_t, std::uint64_t> settle_rest(const NisGate& gate, OnUpdated on_updated,
                                                      NumericalStatus& status) {
    status = NumericalStatus::kOk;
    const std::uint64_t end = collector_.current_step();
    if constexpr (Fusion::kRefuses) {
      if (late_from_) {
        fusion_.reset_to(prior_of(*late_from_));
        status = update_rounds(
            *late_from_, end - 1, gate, [](int, DropKind) {}, on_updated);
        late_from_.reset();
      }
    }
    return {end - std::min<std::uint64_t>(lag(), end), end};
  }

 private:
  // Updates rounds [from, to], the fusion holding round `from`'s prior; screened-out
  // measurements are told to on_refused only for the round closing now.
  template <typename OnRefused, typename OnUpdated>
  NumericalStatus update_rounds(std::uint64_t from, std::uint64_t to, const NisGate& gate,
                                OnRefused on_refused, OnUpdated on_updated) {
    const std::uint64_t closing = collector_.current_step();
    for (std::uint64_t q = from; q <= to; ++q) {
      if (q > from) {
        fusion_.predict();
        if constexpr (Fusion::kRefuses) prior_of(q) = fusion_.state();
      }
      const NumericalStatus status = fusion_.update(
          collector_.station_ids().size(),
          [&](std::size_t j) {
            return collector_.filled_at(q, j) ? &collector_.payload_at(q, j) : nullptr;
          },
          gate,
          [&](int station_id, DropKind why) {
            if (q == closing) on_refused(station_id, why);
          });
      if (status != NumericalStatus::kOk) return status;
      on_updated(q);
    }
    return NumericalStatus::kOk;
  }

  // What a fusion that takes a lag keeps of each round in it: its prior state.
  template <typename F>
  struct PriorOf {
    using type = std::monostate;
  };
  template <typename F>
  requires F::kRefuses struct PriorOf<F> {
    using type = typename F::State;
  };
  auto& prior_of(std::uint64_t step) { return priors_[step % priors_.size()]; }

  Fusion fusion_;
  StepCollector<Observation> collector_;
  std::vector<typename PriorOf<Fusion>::type> priors_;  // each round's prior in the lag
  std::optional<std::uint64_t> late_from_;  // the oldest round a late measurement came for
  std::uint64_t late_used_ = 0;
};

}  // namespace skyfuse
