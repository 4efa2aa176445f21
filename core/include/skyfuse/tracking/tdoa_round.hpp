#pragma once
/// \file
/// The round rule of filter kind "ncrkf" (paper 002's NCRKF run by a station network): each
/// receiver's contribution is its bias-compensated pseudo-linear increment (filters/ncrkf.hpp),
/// which depends on its measurement and its site only, not on the prior; peers fuse them like
/// any increments (round_rule.hpp), and the center, which computes the same increments from
/// the raw measurements, fuses them onto its own prior: the stacked NCRKF in information form.
///
/// One receiver's increment H~^T R^-1 H~ - W may be indefinite (when |r~| < sigma). If the
/// fused information of a round is not positive definite, the round is fused again without
/// every indefinite increment, which are refused as kNotPositive; peers and the center apply
/// the same rule to the same increments and so keep the same bits.

#include <cmath>
#include <optional>

#include "skyfuse/filters/ncrkf.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/tracking/round_rule.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

/// Receiver `observation`'s increment: its pseudo-linear row at its own measurement r~ (sigma
/// from its R), W and V subtracted.
InformationIncrement<PseudoLinearTdoaRow::kDim> tdoa_contribution(
    const StationObservation<RangeDifferenceSensor<PseudoLinearTdoaRow::kDim>>& observation);

/// The shape of a TDOA increment, or of a sum of them: finite, and zero outside [dx, dy, d_t1]
/// (its 3 x 3 block and the first three entries of dy).
std::optional<DropKind> check_tdoa_shape(
    const InformationIncrement<PseudoLinearTdoaRow::kDim>& increment);

/// What a TDOA increment received from a receiver of noise `sigma` must be, since one need not
/// be positive semi-definite: of check_tdoa_shape()'s shape and within check_increment()'s
/// bounds; and no more indefinite than bias compensation can make it, ΔQ + (2 / sigma^2) e3 e3^T
/// positive semi-definite, since H~^T R^-1 H~ is and W_j = 2 / (2 r~^2 + sigma^2) <= 2 / sigma^2.
std::optional<DropKind> check_tdoa_increment(
    const InformationIncrement<PseudoLinearTdoaRow::kDim>& increment, double sigma);

/// Whether an increment is indefinite: the contributions a round that is not positive definite
/// is fused again without.
template <int N>
bool is_indefinite(const InformationIncrement<N>& increment) {
  return check_increment(increment) == DropKind::kNotPositive;
}

/// Fuses a round of TDOA increments into `tracker` by the rule above: slot_at(i) is the i-th
/// participant's slot, as for PeerRound::fuse. If the fused information is not positive
/// definite, the round is fused again without its indefinite increments, on_refused(i) named
/// for each. What the peers, the center and the in-process twin all run.
template <typename Model, typename SlotAt, typename OnRefused>
RoundFusion fuse_tdoa_round(PeerRound<Model>& round, PeerTracker<Model>& tracker,
                            std::size_t participants, SlotAt slot_at, OnRefused on_refused) {
  RoundFusion fused = round.fuse(tracker, slot_at);
  if (fused.status != NumericalStatus::kNotPositiveDefinite) return fused;
  const auto indefinite = [&](const PeerSlot<Model::kDim>& slot) {
    return slot.increment != nullptr && is_indefinite(*slot.increment);
  };
  for (std::size_t i = 0; i < participants; ++i) {
    if (indefinite(slot_at(i))) on_refused(i);
  }
  return round.fuse(tracker, [&](std::size_t i) {
    const PeerSlot<Model::kDim> slot = slot_at(i);
    return indefinite(slot) ? PeerSlot<Model::kDim>{} : slot;
  });
}

}  // namespace skyfuse
