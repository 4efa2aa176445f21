// The TDOA round rule's functions on one receiver's increment (tracking/tdoa_round.hpp), out of
// line: they instantiate the checks' eigen-solvers for the NCRKF's state, which every file
// including the header (every filter part's center and station code) would otherwise compile.
#include "skyfuse/tracking/tdoa_round.hpp"

#include <cmath>

namespace skyfuse {

InformationIncrement<PseudoLinearTdoaRow::kDim> tdoa_contribution(
    const StationObservation<RangeDifferenceSensor<PseudoLinearTdoaRow::kDim>>& observation) {
  const double sigma = std::sqrt(observation.noise(0, 0));
  const PseudoLinearTdoaRow row = pseudo_linear_tdoa_row(observation.sensor.offset(),
                                                         observation.z(0), observation.z(0), sigma);
  return tdoa_increment(observation.station_id, row, BiasCompensation::kCompensated);
}

std::optional<DropKind> check_tdoa_shape(
    const InformationIncrement<PseudoLinearTdoaRow::kDim>& increment) {
  constexpr int kRest = PseudoLinearTdoaRow::kDim - PseudoLinearTdoaRow::kRange - 1;
  if (!increment.delta_information.allFinite() || !increment.delta_vector.allFinite()) {
    return DropKind::kNonFinite;
  }
  const auto& q = increment.delta_information;
  if (!q.bottomRows<kRest>().isZero(0.0) || !q.rightCols<kRest>().isZero(0.0) ||
      !increment.delta_vector.tail<kRest>().isZero(0.0)) {
    return DropKind::kOutOfRange;
  }
  return std::nullopt;
}

std::optional<DropKind> check_tdoa_increment(
    const InformationIncrement<PseudoLinearTdoaRow::kDim>& increment, double sigma) {
  constexpr int kRange = PseudoLinearTdoaRow::kRange;
  if (const auto why = check_tdoa_shape(increment)) return why;
  InformationIncrement<PseudoLinearTdoaRow::kDim> compensated = increment;
  compensated.delta_information(kRange, kRange) += 2.0 / (sigma * sigma);
  return check_increment(compensated);
}

}  // namespace skyfuse
