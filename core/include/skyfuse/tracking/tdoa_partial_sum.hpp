#pragma once
/// \file
/// The NCRKF's partial sum in the tree exchange. The TDOA round rule (tdoa_round.hpp) fuses a
/// round again without its indefinite increments when the fused information is not positive
/// definite, and whether it is is known only from the round's total. So a cluster's sum carries
/// two sums of its members' increments in ascending id: of all of them (the sum the round fuses
/// first), and of the definite ones only (the fallback). The clusters' sums add pairwise, and a
/// peer fuses the total of all, or, if that fails, the total of the definite ones and refuses
/// the rest, as a flat peer and the in-process tree fuse the same round: each of the two totals
/// is summed in the tree's order (fusion/partial_sum.hpp), so every peer holds the same bits.

#include <algorithm>
#include <optional>

#include "skyfuse/fusion/partial_sum.hpp"
#include "skyfuse/tracking/tdoa_round.hpp"
#include "skyfuse/validation/partial_sum_checks.hpp"

namespace skyfuse {

/// The sum of all (this, a PartialSum) and the sum of the definite increments (`definite`).
template <int N>
struct TdoaPartialSum : PartialSum<N> {
  /// The same sum without the indefinite increments: its contributors a subset of these, its
  /// reference the prior of the lowest of them.
  PartialSum<N> definite;

  void clear() {
    PartialSum<N>::clear();
    definite.clear();
  }
  /// Adds station `id`'s increment with its fusion weight, to the fallback too if definite.
  void add(int id, double weight, const InformationIncrement<N>& increment,
           const GaussianState<N>& prior) {
    PartialSum<N>::add(id, weight, increment, prior);
    if (!is_indefinite(increment)) definite.add(id, weight, increment, prior);
  }
  /// Adds a later cluster's sums, each to its own.
  void add(const TdoaPartialSum& later) {
    PartialSum<N>::add(later);
    definite.add(later.definite);
  }
  /// The fallback of a sum of one (a member's own increment): itself, or nothing if indefinite.
  void set_definite_of_one() {
    definite.clear();
    if (!is_indefinite(this->sum)) definite = static_cast<const PartialSum<N>&>(*this);
  }
};

/// Fuses a round's total by the TDOA round rule: the total of all onto its reference; if its
/// information is not positive definite, the total of the definite ones, on_refused(station_id)
/// named for each of the others. What fuse_tdoa_round() does with the same round's slots, in
/// the tree's order of summation.
template <typename Model, typename OnRefused>
RoundFusion fuse_tdoa_total(PeerRound<Model>& round, PeerTracker<Model>& tracker,
                            const TdoaPartialSum<Model::kDim>& total, OnRefused on_refused) {
  const RoundFusion fused = round.fuse_total(tracker, total);
  if (fused.status != NumericalStatus::kNotPositiveDefinite) return fused;
  for (const int id : total.contributors) {
    const auto& kept = total.definite.contributors;
    if (!std::binary_search(kept.begin(), kept.end(), id)) on_refused(id);
  }
  return round.fuse_total(tracker, total.definite);
}

/// What a receiver checks of an NCRKF's sum, whose increments need not be positive
/// semi-definite: the sum of all finite, bounded and zero outside [dx, dy, d_t1] (as
/// check_tdoa_increment() says of one, and within check_increment()'s bounds), with its reference
/// a prior; the fallback a sum of
/// definite increments (check_sum_values()) of some of the same contributors, on the same
/// reference when it starts with the same station.
std::optional<DropKind> check_sum_values(const TdoaPartialSum<PseudoLinearTdoaRow::kDim>& sum);

}  // namespace skyfuse
