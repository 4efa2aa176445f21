#pragma once
/// \file
/// How a station of the `ekf` part turns its own measurement into the increment it sends: the
/// EKF's linearisation at the prior's mean, H^T R^-1 H, H^T R^-1 (nu + H x-), screened by the
/// sensor's checks and the NIS gate (round_rule.hpp). A measurement screened out yields a zero
/// increment, with the reason, so that peers do not wait for one.
///
/// contribute() is defined in ekf_increment_rule_impl.hpp and compiled once per configuration
/// group and sensor in core (src/tracking/filter_rounds_shard.cpp): the Monte Carlo and the
/// station process link it.

#include "skyfuse/tracking/round_rule.hpp"

namespace skyfuse {

struct EkfIncrementRule {
  template <int N, typename Sensor>
  static OwnContribution contribute(const GaussianState<N>& prior,
                                    const StationObservation<Sensor>& observation,
                                    const NisGate& gate, InformationIncrement<N>& out);
};

}  // namespace skyfuse
