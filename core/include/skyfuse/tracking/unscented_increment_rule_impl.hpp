#pragma once
/// \file
/// UnscentedIncrementRule::RoundPrior::contribute (unscented_increment_rule.hpp declares it):
/// one station's increment against the prepared prior. Include this file to run it with a sensor
/// that no configuration group compiles (a picture's, a test's).

#include "skyfuse/tracking/unscented_increment_rule.hpp"

namespace skyfuse {

template <int N>
template <typename Sensor>
OwnContribution UnscentedIncrementRule::RoundPrior<N>::contribute(
    const StationObservation<Sensor>& observation, const NisGate& gate,
    InformationIncrement<N>& out) const {
  constexpr int M = Sensor::kMeasDim;
  if (const auto why = Sensor::check_reported(observation.z)) {
    out.set_zero(observation.station_id);
    return {why, NumericalStatus::kOk};
  }
  const StatisticalLinearisation<M, N> lin =
      linearise(sigma_, observation.sensor, gate.enabled() ? Spread::kForm : Spread::kLeaveOut);
  if (gate.enabled()) {
    const auto nis = unscented_nis(lin, observation.sensor, observation.z, observation.noise);
    if (!nis || *nis > gate.threshold(M)) {
      out.set_zero(observation.station_id);
      return {DropKind::kNisGate, NumericalStatus::kOk};
    }
  }
  return {std::nullopt,
          compute_unscented_increment<N, Sensor>(observation.station_id, sigma_, lin, observation.z,
                                                 observation.noise, out)};
}

}  // namespace skyfuse
