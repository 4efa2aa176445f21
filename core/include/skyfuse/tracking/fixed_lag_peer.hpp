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
/// Only what changed is fused again: the rounds from the oldest one that took a late
/// contribution, or from b if its reference prior is not the chain's own prior of b (bit for
/// bit); the rounds before keep the posteriors stored when they were fused, which a full pass
/// from b would give again. Without late samples a round costs one fusion, whatever L.
///
/// How one round's slots are fused is the caller's (fuse_round(step, slot_at), e.g.
/// PeerRound::fuse, or the TDOA round rule); the chain is the same for every filter. No
/// allocation per round.

#include <algorithm>
#include <cstdint>
#include <cstring>
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

  /// `ids` the participants, ascending, with their fusion `weights` in that order; `fanout`
  /// as PeerRound takes it (0: the flat exchange).
  FixedLagPeer(const Model& motion, const State& initial, std::span<const int> ids,
               std::span<const double> weights, std::size_t lag, std::size_t fanout = 0)
      : tracker_(motion, initial),
        collector_(ids, lag),
        round_(collector_.station_ids(), weights, fanout),
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
    dirty_from_ = std::min(dirty_from_.value_or(step), step);
  }
  /// Contributions kept although their round had closed, so far.
  std::uint64_t late_used() const { return late_used_; }

  /// Brings the tracker to the prior of the current round with every contribution that has
  /// arrived, late ones included: what a peer's own contribution is computed against.
  template <typename FuseRound>
  NumericalStatus refresh_prior(FuseRound fuse_round) {
    const std::uint64_t c = collector_.current_step();
    if (!dirty_from_ || c == first_) return NumericalStatus::kOk;
    const RoundFusion fused = fuse_rounds(c - 1, fuse_round);
    if (fused.status != NumericalStatus::kOk) return fused.status;
    predict();
    return NumericalStatus::kOk;
  }

  /// Fuses the current round, and again the lag's rounds before it: fuse_round(step, slot_at)
  /// fuses one round's slots into tracker() (slot_at(i): the i-th participant's, ascending id)
  /// as PeerRound::fuse does. The current round's result.
  template <typename FuseRound>
  RoundFusion fuse_current(FuseRound fuse_round) {
    return fuse_rounds(collector_.current_step(), fuse_round);
  }
  /// The tree exchange (no lag): cluster c's sum of the current round's contributions, each
  /// with its own prior (PeerRound::sum_cluster): what the cluster's aggregator publishes.
  /// `Sum`: a PartialSum<kDim>, or one that adds more per station (TdoaPartialSum).
  template <typename Sum>
  void sum_cluster_current(std::size_t c, Sum& out) const {
    const std::uint64_t q = collector_.current_step();
    round_.sum_cluster(
        c,
        [&](std::size_t i) -> PeerSlot<kDim> {
          if (!collector_.filled_at(q, i)) return {};
          const Contribution& contribution = collector_.payload_at(q, i);
          return {&contribution.increment, &contribution.prior};
        },
        out);
  }
  /// The tree exchange (no lag): fuses the current round's total onto its reference.
  RoundFusion fuse_total_current(const PartialSum<kDim>& total) {
    return round_.fuse_total(tracker_, total);
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
    if (keeps_history()) prior_of(collector_.current_step() + 1) = tracker_.estimate();
  }
  void advance() { collector_.advance(); }

 private:
  State& prior_of(std::uint64_t step) { return priors_[step % priors_.size()]; }
  std::uint64_t base_round() const {
    const std::uint64_t c = collector_.current_step();
    return c - std::min<std::uint64_t>(collector_.lag(), c - first_);
  }

  // With a lag, each round's prior, posterior and contributors are kept; without, nothing is
  // fused again and nothing need be.
  bool keeps_history() const { return collector_.lag() != 0; }

  // Whether round `base`'s reference prior (the lowest-id contribution's) is no longer,
  // bit for bit, the chain's own prior of it, under which the round was last fused.
  bool reference_moved(std::uint64_t base) {
    const auto ids = collector_.station_ids();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (!collector_.filled_at(base, i)) continue;
      const State& reference = collector_.payload_at(base, i).prior;
      const State& own = prior_of(base);
      return std::memcmp(reference.mean.data(), own.mean.data(), sizeof(double) * kDim) != 0 ||
             std::memcmp(reference.covariance.data(), own.covariance.data(),
                         sizeof(double) * kDim * kDim) != 0;
    }
    return false;  // nothing arrived: fused onto the chain's own prior, as before
  }

  // Fuses the rounds through `last` that may have changed (see the file comment), the base
  // round by the round rule and the later ones onto the chain's own prior, storing each prior,
  // posterior and contributor list as it is reached. The last round fused's result; nothing
  // fused, kOk.
  template <typename FuseRound>
  RoundFusion fuse_rounds(std::uint64_t last, FuseRound fuse_round) {
    const std::uint64_t c = collector_.current_step();
    const std::uint64_t base = base_round();
    std::uint64_t from = last == c ? c : last + 1;  // the current round is new: always fused
    if (dirty_from_) from = std::min(from, std::max(*dirty_from_, base));
    if (base < from && base < c && reference_moved(base)) from = base;
    dirty_from_.reset();
    // Entering the current round the tracker holds its prior already (predict()).
    if (from < c) tracker_.reset_to(prior_of(from));
    RoundFusion result;
    for (std::uint64_t q = from; q <= last; ++q) {
      if (q > from) {
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
      if (!keeps_history()) continue;
      posteriors_[q % posteriors_.size()] = tracker_.estimate();
      std::vector<int>& fused_from = contributors_[q % contributors_.size()];
      fused_from.assign(round_.contributors().begin(), round_.contributors().end());
    }
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
  std::optional<std::uint64_t> dirty_from_;  // the oldest round a late contribution came for
};

}  // namespace skyfuse
