#pragma once
// What a station fuses when the run's filter part has an increment rule (the EKF, the unscented
// filter) on one motion model (any registered one): one increment per station and round, fused
// onto the lowest-id contribution's prior
// (tracking/round_rule.hpp). The station process (station_process.cpp) moves the samples; this
// decides what they mean. ImmFusion (imm_fusion.hpp) and NcrkfFusion (ncrkf_fusion.hpp) have the
// same interface.

#include <cstdint>
#include <optional>
#include <utility>

#include "increment_round.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::station {

/// The station's sensing (station_sensing.hpp) makes its increment by the filter part's rule.
template <typename Model>
class SingleModelFusion : public IncrementRound<Model> {
  using Base = IncrementRound<Model>;

 public:
  using Base::Base;
  using typename Base::Contribution;
  using typename Base::Sensing;

  /// Screens this station's own measurement, last taken by `sensing`, against the common prior,
  /// writes its contribution (write(sample)) and keeps it for the round.
  template <typename Write>
  OwnContribution contribute(std::uint64_t k, const Sensing& sensing, const NisGate& gate,
                             std::uint64_t run_id, Write write) {
    OwnContribution result;
    result.status = this->chain_.refresh_prior(fuse_one_round());
    if (result.status != NumericalStatus::kOk) return result;
    Contribution own;
    own.prior = this->chain_.tracker().estimate();
    result = sensing.contribute(own.prior, gate, own.increment);
    if (result.status != NumericalStatus::kOk) return result;
    this->publish(k, sensing.station_id(), own, run_id, write);
    return result;
  }

  /// Checks a peer's sample (its run id already checked) and keeps it; why not if it did not.
  std::optional<DropKind> admit(const wire::InformationIncrement& sample,
                                const transport::WriterId& writer,
                                transport::SourceBinding& sources) {
    return this->admit_checked(sample, writer, sources, [](const Contribution& contribution) {
      return check_contribution(contribution);
    });
  }

  /// Checks a peer's contribution to `step` that came another way than its own sample (a tree
  /// exchange's member to its aggregator) and keeps it; why not if it did not.
  /// `one`: the contribution as a sum of one (its sender's, unweighted).
  std::optional<DropKind> admit_contribution(std::uint64_t step, int station_id,
                                             const typename Base::TreeSum& one,
                                             const transport::WriterId& writer,
                                             transport::SourceBinding& sources) {
    const Contribution contribution{one.sum, one.reference};
    if (const auto why = check_contribution(contribution)) return why;
    return this->keep(step, station_id, writer, sources, contribution);
  }

  /// Fuses what arrived; arrived() then says whether anything did. Refuses nothing at fusion
  /// (on_refused(station_id, why) is never called): every sample was checked on arrival.
  template <typename OnRefused>
  RoundFusion fuse(OnRefused /*on_refused*/) {
    return this->chain_.fuse_current(fuse_one_round());
  }

  /// The end of the run: the rounds still in the lag, final now (settled_track()).
  std::pair<std::uint64_t, std::uint64_t> settle(NumericalStatus& status) {
    return this->chain_.settle_rest(fuse_one_round(), status);
  }

 private:
  // One round by the round rule.
  auto fuse_one_round() {
    return [this](std::uint64_t /*step*/, auto slot_at) {
      return this->chain_.round().fuse(this->chain_.tracker(), slot_at);
    };
  }
};

}  // namespace skyfuse::station
