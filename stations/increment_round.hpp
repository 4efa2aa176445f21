#pragma once
// What a station's fusion of one increment per station and round shares, whatever makes the
// increments: the tracker over `Model`, the collector of the round's contributions by station,
// and the round rule that fuses them onto the lowest-id contribution's prior
// (tracking/round_rule.hpp). SingleModelFusion (the EKF's increments) and NcrkfFusion (paper
// 002's bias-compensated ones) derive from it and differ in how an increment is made, checked
// and fused.
//
// Fixed-lag re-fusion (`--refusion-lag L`): the collector also keeps late contributions for
// the L rounds closed last, and each round is fused again from round b = c - L on: round b by
// the round rule (onto the lowest-id contribution's prior), the later ones onto this node's own
// chain. So a late contribution still counts, and peers that hold the same contributions for
// rounds b..c hold the same bits. L = 0 is the round rule alone; without late samples every L
// gives the same bits, since each sender's prior is then the chain's.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

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

  explicit IncrementRound(const RunPlan& plan, std::size_t lag = 0)
      : tracker_(plan.motion_model<Model>(), plan.initial_estimate<Model>()),
        collector_(plan.participant_ids(), lag),
        round_(collector_.station_ids(), plan.weights_of(collector_.station_ids())),
        priors_(lag + 1, tracker_.estimate()),
        posteriors_(lag + 1, tracker_.estimate()),
        contributors_(lag + 1) {
    for (std::vector<int>& c : contributors_) c.reserve(collector_.station_ids().size());
  }

  std::span<const int> station_ids() const { return collector_.station_ids(); }
  void start_at(std::uint64_t step) {
    collector_.start_at(step);
    first_ = step;
    prior_of(step) = tracker_.estimate();
  }
  /// Contributions kept although their round had closed (re-fused), so far.
  std::uint64_t late_used() const { return late_used_; }

  /// With a lag, the round whose estimate the last fuse() made final: the oldest in the lag,
  /// which leaves it at the next advance().
  std::optional<std::uint64_t> settled_round() const {
    const std::uint64_t c = collector_.current_step();
    if (collector_.lag() == 0 || c < first_ + collector_.lag()) return std::nullopt;
    return c - collector_.lag();
  }
  /// The end of the run, after the last advance(): every round still in the lag fused again
  /// with what has come since, all of them final now. The rounds, oldest first.
  template <typename FuseRound>
  std::pair<std::uint64_t, std::uint64_t> settle_rest(FuseRound fuse_round,
                                                      NumericalStatus& status) {
    const std::uint64_t c = collector_.current_step();
    const std::uint64_t base = c - std::min<std::uint64_t>(collector_.lag(), c - first_);
    status = base < c ? fuse_rounds(c - 1, fuse_round).status : NumericalStatus::kOk;
    return {base, c};
  }
  /// The final track of a settled round (settled_round(), or one of settle_rest()'s).
  wire::TrackEstimate settled_track(std::uint64_t run_id, std::uint64_t step,
                                    int station_id) const {
    wire::TrackEstimate track = transport::to_wire(
        posteriors_[step % posteriors_.size()], run_id, static_cast<std::uint32_t>(step),
        station_id, wire::PEER, contributors_[step % contributors_.size()]);
    track.settled(true);
    return track;
  }

  /// Stations whose contribution to the current round is in.
  std::size_t arrived_count() const { return collector_.count(); }
  /// Whether anything arrived for the last fuse().
  bool arrived() const { return round_.arrived(); }

  /// The fused track of the round just fused.
  wire::TrackEstimate track(std::uint64_t run_id, std::uint64_t k, int station_id) const {
    return transport::to_wire(tracker_.estimate(), run_id, static_cast<std::uint32_t>(k),
                              station_id, wire::PEER, round_.contributors());
  }

  void predict() {
    tracker_.predict();
    prior_of(collector_.current_step() + 1) = tracker_.estimate();
  }
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
    const auto why = transport::admit(collector_, sources, sample.step(), sample.station_id(),
                                      writer, contribution);
    if (!why && sample.step() < collector_.current_step()) {
      ++late_used_;
      late_since_fused_ = true;
    }
    return why;
  }

  /// Brings the tracker to the prior of the current round with every contribution that has
  /// arrived, late ones included: what this station's own contribution is computed against.
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
  /// fuses one round's slots into tracker_ (slot_at(i): the i-th participant's, ascending id)
  /// and returns what PeerRound::fuse returns. The current round's result.
  template <typename FuseRound>
  RoundFusion fuse_current(FuseRound fuse_round) {
    return fuse_rounds(collector_.current_step(), fuse_round);
  }

  /// Whether round `step` is the one being closed, not one fused again.
  bool is_current(std::uint64_t step) const { return step == collector_.current_step(); }

  PeerTracker<Model> tracker_;
  StepCollector<Contribution> collector_;
  PeerRound<Model> round_;

 private:
  GaussianState<kDim>& prior_of(std::uint64_t step) { return priors_[step % priors_.size()]; }

  // Rounds b = max(current - lag, first) through `last`, from round b's prior: round b onto
  // the lowest-id contribution's prior (this node's own if none arrived), the later ones onto
  // the chain's own, each prior stored as it is reached.
  template <typename FuseRound>
  RoundFusion fuse_rounds(std::uint64_t last, FuseRound fuse_round) {
    const std::uint64_t c = collector_.current_step();
    const std::uint64_t base = c - std::min<std::uint64_t>(collector_.lag(), c - first_);
    RoundFusion result;
    for (std::uint64_t q = base; q <= last; ++q) {
      if (q == base) {
        tracker_.reset_to(prior_of(q));
      } else {
        tracker_.predict();
        prior_of(q) = tracker_.estimate();
      }
      const GaussianState<kDim>* own = q == base ? nullptr : &prior_of(q);
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

  std::vector<GaussianState<kDim>> priors_;      // the chain's prior of each round in the lag
  std::vector<GaussianState<kDim>> posteriors_;  // and its posterior
  std::vector<std::vector<int>> contributors_;   // and the stations fused into it
  std::uint64_t first_ = 0;                      // the first round this node fuses
  std::uint64_t late_used_ = 0;
  bool late_since_fused_ = false;
};

}  // namespace skyfuse::station
