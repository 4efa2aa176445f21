#pragma once
/// \file
/// EkfIncrementRule::contribute (ekf_increment_rule.hpp declares it): the round rule's
/// contribution. Include this file to run it with a sensor that no configuration group compiles
/// (a picture's, a test's).

#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

template <int N, typename Sensor>
OwnContribution EkfIncrementRule::contribute(const GaussianState<N>& prior,
                                             const StationObservation<Sensor>& observation,
                                             const NisGate& gate, InformationIncrement<N>& out) {
  return skyfuse::contribute(prior, observation, gate, out);
}

}  // namespace skyfuse
