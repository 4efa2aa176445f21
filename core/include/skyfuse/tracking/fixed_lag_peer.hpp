#pragma once
/// \file
/// A peer's rounds with fixed-lag re-fusion (`--refusion-lag L`): the tracker, the collector of
/// each round's contributions by station (which keeps late ones for the L rounds closed last),
/// and the chain of each round's prior and posterior in the lag. Each round c is fused from
/// round b = max(c - L, first) on: round b by the round rule (round_rule.hpp), onto the
/// lowest-id contribution's prior (this peer's own if none arrived), and rounds b + 1 .. c onto
/// the chain's own prior. So a late contribution still counts, and peers that hold the same
/// contributions for rounds b .. c hold the same bits. L = 0 is the round rule alone; without
/// late samples every L gives the bits of L = 0, since each sender's prior is then the chain's.
///
/// How one round's slots are fused is the caller's (fuse_round(step, slot_at), e.g.
/// PeerRound::fuse, or the TDOA round rule); the chain is the same for every filter. No
/// allocation per round.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/tracking/step_collector.hpp"

namespace skyfuse {

template <typename Model>
class FixedLagPeer {
 public:
  static constexpr int kDim = Model::kDim;
  using State = GaussianState<kDim>;
  using Contribution = PeerContribution<kDim>;

  /// `ids` the participants, ascending, with their fusion `weights` in that order.
  FixedLagPeer(const Model& motion, const State& initial, std::span<const int> ids,
               std::span<const double> weights, std::size_t lag)
      : tracker_(motion, initial),
        collector_(ids, lag),
        round_(collector_.station_ids(), weights),
        priors_(lag + 1, initial),
        posteriors_(lag + 1, initial),
        contributors_(lag + 1) {
    for (std::vector<int>& c : contributors_) c.reserve(collector_.station_ids().size());
  }

  /// Starts at `step` (a process that joins late), with the tracker's estimate as its prior.
  void start_at(std::uint64_t step) {
    collector_.start_at(step);
    first_ = step;
    prior_of(step) = tracker_.estimate();
  }

  StepCollector<Contribution>& collector() { return collector_; }
  const StepCollector<Contribution>& collector() const { return collector_; }
  PeerTracker<Model>& tracker() { return tracker_; }
  const PeerTracker<Model>& tracker() const { return tracker_; }
  PeerRound<Model>& round() { return round_; }
  const PeerRound<Model>& round() const { return round_; }

  /// Tells the chain a contribution for `step` was kept: one for a closed round is late, and
  /// the chain is fused again before it is used.
  void kept(std::uint64_t step) {
    if (step >= collector_.current_step()) return;
    ++late_used_;
    late_since_fused_ = true;
  }
  /// Contributions kept although their round had closed, so far.
  std::uint64_t late_used() const { return late_used_; }

  /// Brings the tracker to the prior of the current round with every contribution that has
  /// arrived, late ones included: what a peer's own contribution is computed against.
  template <typename FuseRound>
  NumericalStatus refresh_prior(FuseRound fuse_round) {
    const std::uint64_t c = collector_.current_step();
    if (!late_since_fused_ || c == first_) return NumericalStatus::kOk;
    const RoundFusion fused = fuse_rounds(c - 1, fuse_round);
    if (fused.status != NumericalStatus::kOk) return fused.status;
    tracker_.predict();
    prior_of(c) = tracker_.estimate();
    return NumericalStatus::kOk;
  }

  /// Fuses the current round, and again the lag's rounds before it: fuse_round(step, slot_at)
  /// fuses one round's slots into tracker() (slot_at(i): the i-th participant's, ascending id)
  /// as PeerRound::fuse does. The current round's result.
  template <typename FuseRound>
  RoundFusion fuse_current(FuseRound fuse_round) {
    return fuse_rounds(collector_.current_step(), fuse_round);
  }
  /// Whether round `step` is the one being closed, not one fused again.
  bool is_current(std::uint64_t step) const { return step == collector_.current_step(); }

  /// After fuse_current(), with a lag: the round whose estimate is final now, the oldest in
  /// the lag, which leaves it at the next advance().
  std::optional<std::uint64_t> settled_round() const {
    const std::uint64_t c = collector_.current_step();
    if (collector_.lag() == 0 || c < first_ + collector_.lag()) return std::nullopt;
    return c - collector_.lag();
  }
  /// The end of the run, after the last advance(): every round still in the lag fused again
  /// with what has come since, all final now. The rounds [first, end).
  template <typename FuseRound>
  std::pair<std::uint64_t, std::uint64_t> settle_rest(FuseRound fuse_round,
                                                      NumericalStatus& status) {
    const std::uint64_t c = collector_.current_step();
    const std::uint64_t base = base_round();
    status = base < c ? fuse_rounds(c - 1, fuse_round).status : NumericalStatus::kOk;
    return {base, c};
  }
  /// A round's posterior and the stations fused into it, as the chain last fused it (a round
  /// in the lag).
  const State& posterior_of(std::uint64_t step) const {
    return posteriors_[step % posteriors_.size()];
  }
  std::span<const int> contributors_of(std::uint64_t step) const {
    return contributors_[step % contributors_.size()];
  }

  void predict() {
    tracker_.predict();
    prior_of(collector_.current_step() + 1) = tracker_.estimate();
  }
  void advance() { collector_.advance(); }

 private:
  State& prior_of(std::uint64_t step) { return priors_[step % priors_.size()]; }
  std::uint64_t base_round() const {
    const std::uint64_t c = collector_.current_step();
    return c - std::min<std::uint64_t>(collector_.lag(), c - first_);
  }

  // Rounds base_round() through `last`, from the base's prior: the base onto the lowest-id
  // contribution's prior (this peer's own if none arrived), the later ones onto the chain's
  // own, each prior, posterior and contributor list stored as it is reached.
  template <typename FuseRound>
  RoundFusion fuse_rounds(std::uint64_t last, FuseRound fuse_round) {
    const std::uint64_t base = base_round();
    RoundFusion result;
    for (std::uint64_t q = base; q <= last; ++q) {
      if (q == base) {
        tracker_.reset_to(prior_of(q));
      } else {
        tracker_.predict();
        prior_of(q) = tracker_.estimate();
      }
      const State* own = q == base ? nullptr : &prior_of(q);
      result = fuse_round(q, [&, q, own](std::size_t i) -> PeerSlot<kDim> {
        if (!collector_.filled_at(q, i)) return {};
        const Contribution& contribution = collector_.payload_at(q, i);
        return {&contribution.increment, own != nullptr ? own : &contribution.prior};
      });
      if (result.status != NumericalStatus::kOk) return result;
      posteriors_[q % posteriors_.size()] = tracker_.estimate();
      std::vector<int>& fused_from = contributors_[q % contributors_.size()];
      fused_from.assign(round_.contributors().begin(), round_.contributors().end());
    }
    late_since_fused_ = false;
    return result;
  }

  PeerTracker<Model> tracker_;
  StepCollector<Contribution> collector_;
  PeerRound<Model> round_;
  std::vector<State> priors_;                   // the chain's prior of each round in the lag
  std::vector<State> posteriors_;               // and its posterior
  std::vector<std::vector<int>> contributors_;  // and the stations fused into it
  std::uint64_t first_ = 0;                     // the first round this peer fuses
  std::uint64_t late_used_ = 0;
  bool late_since_fused_ = false;
};

}  // namespace skyfuse
