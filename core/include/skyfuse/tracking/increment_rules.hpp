#pragma once
/// \file
/// How a station turns its own measurement into the increment it sends, for the filters whose
/// contribution is one information increment against the common prior (every peer sums them by
/// the round rule): the EKF's linearisation at the prior's mean, or the unscented filter's
/// statistical linearisation over the prior's sigma points (filters/unscented.hpp). Either
/// yields a zero increment, with the reason, for a measurement screened out, so that peers do
/// not wait for one.

#include "skyfuse/filters/unscented.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

/// The EKF's increment, screened by the sensor's checks and the NIS gate (round_rule.hpp).
struct EkfIncrementRule {
  template <int N, typename Sensor>
  static OwnContribution contribute(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& observation,
                                    const NisGate& gate, InformationIncrement<N>& out) {
    return skyfuse::contribute(prior, observation, gate, out);
  }
};

/// The unscented information filter's increment, screened by the sensor's checks. Its part
/// takes no NIS gate: a gate would need the unscented innovation covariance, not the EKF's.
struct UnscentedIncrementRule {
  /// A station's own increment: it makes the prior's sigma points for its one measurement.
  template <int N, typename Sensor>
  static OwnContribution contribute(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& observation,
                                    const NisGate& /*gate*/, InformationIncrement<N>& out) {
    if (const auto why = Sensor::check_reported(observation.z)) {
      out.set_zero(observation.station_id);
      return {why, NumericalStatus::kOk};
    }
    SigmaPoints<N> sigma;
    if (!sigma.compute(prior, UnscentedParameters{})) {
      return {std::nullopt, NumericalStatus::kNotPositiveDefinite};
    }
    return contribute(sigma, observation, out);
  }

  /// The same against sigma points made once for the round: a center or an in-process twin
  /// computes every station's increment against one prior.
  template <int N, typename Sensor>
  static OwnContribution contribute(const SigmaPoints<N>& sigma,
                                    const StationObservation<Sensor>& observation,
                                    InformationIncrement<N>& out) {
    if (const auto why = Sensor::check_reported(observation.z)) {
      out.set_zero(observation.station_id);
      return {why, NumericalStatus::kOk};
    }
    return {std::nullopt,
            compute_unscented_increment(observation.station_id, sigma, observation.sensor,
                                        observation.z, observation.noise, out)};
  }
};

}  // namespace skyfuse
