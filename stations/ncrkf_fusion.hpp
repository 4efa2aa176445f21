#pragma once
// What a station fuses when the run's filter is paper 002's NCRKF (kind ncrkf): one
// bias-compensated pseudo-linear increment per receiver and round, which depends on the
// receiver's measurement and site only (tracking/tdoa_round.hpp), fused onto the lowest-id
// contribution's prior by the TDOA round rule. A received increment need not be positive
// semi-definite, so it is checked by check_tdoa_increment() against its sender's noise, not by
// check_increment(). Same interface as SingleModelFusion (single_model_fusion.hpp).

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "increment_round.hpp"
#include "skyfuse/core/sorted_ids.hpp"
#include "skyfuse/models/tdoa/tdoa_relative_motion.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/tracking/tdoa_partial_sum.hpp"
#include "skyfuse/tracking/tdoa_round.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse::station {

class NcrkfFusion : public IncrementRound<TdoaRelativeMotion> {
 public:
  using Model = TdoaRelativeMotion;
  using Sensor = RangeDifferenceSensor<kDim>;

  NcrkfFusion(const RunPlan& plan, std::size_t lag) : IncrementRound(plan, lag) {
    for (const int id : station_ids()) {
      sigmas_.push_back(std::sqrt(station_noise_covariance<Sensor::kMeasDim>(
          plan.scenario, *plan.participant(id), plan.mc_run)(0, 0)));
    }
  }

  /// This station's increment for its own measurement, last taken by `sensing` (write(sample)),
  /// kept for the round. The NCRKF has no innovation to screen (its part refuses a NIS gate): a
  /// measurement that fails its sensor's check yields a zero increment, which tells the peers
  /// not to wait for one.
  template <typename Write>
  OwnContribution contribute(std::uint64_t k, const Sensing& sensing, const NisGate& gate,
                             std::uint64_t run_id, Write write) {
    OwnContribution result;
    result.status = chain_.refresh_prior(fuse_one_round([](int, DropKind) {}));
    if (result.status != NumericalStatus::kOk) return result;
    Contribution own;
    own.prior = chain_.tracker().estimate();
    result = sensing.contribute(own.prior, gate, own.increment);
    publish(k, sensing.station_id(), own, run_id, write);
    return result;
  }

  /// Checks a peer's sample (its run id already checked) against its sender's noise and keeps
  /// it; why not if it did not.
  std::optional<DropKind> admit(const wire::InformationIncrement& sample,
                                const transport::WriterId& writer,
                                transport::SourceBinding& sources) {
    return admit_checked(sample, writer, sources, [&](const Contribution& contribution) {
      return check_from(static_cast<int>(sample.station_id()), contribution);
    });
  }

  // The tree exchange (tree_exchange.hpp): sums of all increments and of the definite ones.

  /// The sum the tree adds and fuses.
  using TreeSum = TdoaPartialSum<kDim>;
  /// `out` := this station's kept contribution as a sum of one, unweighted, with its fallback;
  /// false if none is kept.
  bool own_sum(int station_id, TreeSum& out) const {
    if (!IncrementRound::own_sum(station_id, out)) return false;
    out.set_definite_of_one();
    return true;
  }
  /// Checks a member's contribution to `step` (`one`: its increment as a sum of one) against
  /// its sender's noise, as admit() does a sample, and keeps it; why not if it did not.
  std::optional<DropKind> admit_contribution(std::uint64_t step, int station_id, const TreeSum& one,
                                             const transport::WriterId& writer,
                                             transport::SourceBinding& sources) {
    const Contribution contribution{one.sum, one.reference};
    if (const auto why = check_from(station_id, contribution)) return why;
    return keep(step, station_id, writer, sources, contribution);
  }
  /// Cluster c's sums of the current round's contributions.
  void sum_cluster(std::size_t c, TreeSum& out) const { chain_.sum_cluster_current(c, out); }
  /// Fuses the current round's total of all by the TDOA round rule: if its information is not
  /// positive definite, the total of the definite ones, on_refused(station_id, kNotPositive)
  /// named for each of the others. arrived() then says whether it counted anyone.
  template <typename OnRefused>
  RoundFusion fuse_total(const TreeSum& total, OnRefused on_refused) {
    return fuse_tdoa_total(chain_.round(), chain_.tracker(), total,
                           [&](int id) { on_refused(id, DropKind::kNotPositive); });
  }

  /// Fuses what arrived by the TDOA round rule; on_refused(station_id, kNotPositive) for each
  /// indefinite increment the round had to be fused without. arrived() then says whether
  /// anything did.
  template <typename OnRefused>
  RoundFusion fuse(OnRefused on_refused) {
    return chain_.fuse_current(fuse_one_round(on_refused));
  }

 private:
  // One round by the TDOA round rule; refusals are reported for the round being closed only,
  // not again when a later round fuses it again.
  template <typename OnRefused>
  auto fuse_one_round(OnRefused on_refused) {
    return [this, on_refused](std::uint64_t step, auto slot_at) {
      const auto ids = station_ids();
      return fuse_tdoa_round(chain_.round(), chain_.tracker(), ids.size(), slot_at,
                             [&](std::size_t i) {
                               if (chain_.is_current(step))
                                 on_refused(ids[i], DropKind::kNotPositive);
                             });
    };
  }

  // What a contribution from `station_id` must be, however it came: its increment against that
  // receiver's noise, its prior as an estimate. An unknown sender has no noise to check against;
  // keep() refuses it by name.
  std::optional<DropKind> check_from(int station_id, const Contribution& contribution) const {
    const auto sender = position_of(station_ids(), station_id);
    if (!sender) return std::nullopt;
    if (const auto why = check_tdoa_increment(contribution.increment, sigmas_[*sender])) return why;
    return check_estimate(contribution.prior);
  }

  std::vector<double> sigmas_;  // each participant's range-difference noise, ascending id

 public:
  /// The end of the run: the rounds still in the lag, final now (settled_track()).
  std::pair<std::uint64_t, std::uint64_t> settle(NumericalStatus& status) {
    return chain_.settle_rest(fuse_one_round([](int, DropKind) {}), status);
  }
};

}  // namespace skyfuse::station
