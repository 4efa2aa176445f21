// A receiver's check of an NCRKF's partial sum (tracking/tdoa_partial_sum.hpp), out of line for
// the same reason as tdoa_round.cpp: the checks it calls are costly to compile.
#include "skyfuse/tracking/tdoa_partial_sum.hpp"

#include <algorithm>

namespace skyfuse {

std::optional<DropKind> check_sum_values(const TdoaPartialSum<PseudoLinearTdoaRow::kDim>& sum) {
  const auto& all = sum.sum;
  if (const auto why = check_tdoa_shape(all)) return why;
  if (all.delta_information.cwiseAbs().maxCoeff() > kMaxInformation ||
      all.delta_vector.cwiseAbs().maxCoeff() > kMaxInformation * kMaxRangeM) {
    return DropKind::kOutOfRange;
  }
  if (sum.empty()) {
    const bool zero = all.delta_information.isZero(0.0) && all.delta_vector.isZero(0.0);
    if (!zero || !sum.definite.empty()) return DropKind::kOutOfRange;
    return std::nullopt;
  }
  if (all.station_id != sum.contributors.front()) return DropKind::kOutOfRange;
  if (const auto why = check_estimate(sum.reference)) return why;
  if (const auto why = check_sum_values(sum.definite)) return why;
  if (!std::includes(sum.contributors.begin(), sum.contributors.end(),
                     sum.definite.contributors.begin(), sum.definite.contributors.end())) {
    return DropKind::kOutOfRange;
  }
  const bool same_first =
      !sum.definite.empty() && sum.definite.contributors.front() == sum.contributors.front();
  if (same_first && (sum.definite.reference.mean != sum.reference.mean ||
                     sum.definite.reference.covariance != sum.reference.covariance)) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

}  // namespace skyfuse
