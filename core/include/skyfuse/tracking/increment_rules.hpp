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
  template <int N, typename Sensor>
  static OwnContribution contribute(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& observation,
                                    const NisGate& /*gate*/, InformationIncrement<N>& out) {
    OwnContribution result;
    result.refused = Sensor::check_reported(observation.z);
    if (result.refused) {
      out.station_id = observation.station_id;
      out.delta_information.setZero();
      out.delta_vector.setZero();
      return result;
    }
    SigmaPoints<N> sigma;
    if (!sigma.compute(prior, UnscentedParameters{})) {
      result.status = NumericalStatus::kNotPositiveDefinite;
      return result;
    }
    result.status = compute_unscented_increment(observation.station_id, sigma, observation.sensor,
                                                observation.z, observation.noise, out);
    return result;
  }
};

}  // namespace skyfuse
