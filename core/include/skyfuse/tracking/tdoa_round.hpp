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

#include "skyfuse/filters/ncrkf.hpp"
#include "skyfuse/fusion/station_observation.hpp"
#include "skyfuse/models/tdoa/range_difference_sensor.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {

/// Receiver `observation`'s increment: its pseudo-linear row at its own measurement r~ (sigma
/// from its R), W and V subtracted.
inline InformationIncrement<PseudoLinearTdoaRow::kDim> tdoa_contribution(
    const StationObservation<RangeDifferenceSensor<PseudoLinearTdoaRow::kDim>>& observation) {
  const double sigma = std::sqrt(observation.noise(0, 0));
  const PseudoLinearTdoaRow row = pseudo_linear_tdoa_row(observation.sensor.offset(),
                                                         observation.z(0), observation.z(0), sigma);
  return tdoa_increment(observation.station_id, row, BiasCompensation::kCompensated);
}

/// Whether an increment is indefinite: the contributions a round that is not positive definite
/// is fused again without.
template <int N>
bool is_indefinite(const InformationIncrement<N>& increment) {
  return check_increment(increment) == DropKind::kNotPositive;
}

}  // namespace skyfuse
