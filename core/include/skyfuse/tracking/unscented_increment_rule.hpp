#pragma once
/// \file
/// How a station of the `ukf` part turns its own measurement into the increment it sends: the
/// unscented filter's statistical linearisation over the prior's sigma points
/// (filters/unscented.hpp), screened by the sensor's checks and the NIS gate on the unscented
/// innovation covariance P_zz + R. A measurement screened out yields a zero increment, with the
/// reason, so that peers do not wait for one. The center compares its sum of these increments
/// with the covariance-form UKF on the stacked measurement (the rule's reference update).

#include <span>
#include <string_view>

#include "skyfuse/filters/unscented.hpp"
#include "skyfuse/filters/unscented_covariance_update.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

struct UnscentedIncrementRule {
  /// The prior a round's increments are computed against, prepared once for every station:
  /// its sigma points.
  template <int N>
  class RoundPrior {
   public:
    /// False if the prior's covariance is not positive definite.
    bool prepare(const GaussianState<N>& prior) {
      return sigma_.compute(prior, UnscentedParameters{});
    }

    /// One station's increment against the prepared prior, into `out` (defined in
    /// unscented_increment_rule_impl.hpp, compiled once per configuration group and sensor in
    /// core: src/tracking/filter_rounds_shard.cpp).
    template <typename Sensor>
    OwnContribution contribute(const StationObservation<Sensor>& observation, const NisGate& gate,
                               InformationIncrement<N>& out) const;

    static constexpr std::string_view kReferenceName = "the covariance-form UKF";
    /// The covariance-form UKF's update of `prior` (the prepared one) with the stacked
    /// observations: what the center measures its distance to.
    template <typename Observation>
    NumericalStatus reference_update(const GaussianState<N>& prior,
                                     std::span<const Observation* const> stacked,
                                     GaussianState<N>& posterior) const {
      return covariance_form_unscented_update(sigma_, prior, stacked, posterior);
    }

   private:
    SigmaPoints<N> sigma_;
  };

  /// A station's own increment: it prepares the prior for its one measurement.
  template <int N, typename Sensor>
  static OwnContribution contribute(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& observation,
                                    const NisGate& gate, InformationIncrement<N>& out) {
    RoundPrior<N> round_prior;
    if (!round_prior.prepare(prior)) return {std::nullopt, NumericalStatus::kNotPositiveDefinite};
    return round_prior.contribute(observation, gate, out);
  }
};

}  // namespace skyfuse
