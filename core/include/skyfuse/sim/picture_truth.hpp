#pragma once
/// \file
/// The aircraft a picture is scored against at a step: those present, each marked whether at
/// least one of the run's stations could see it (a cooperative station only one with an
/// address) and whether it has an address. Shared by the in-process run and the harness
/// of a run over DDS, so that both score the same way.

#include <vector>

#include "skyfuse/metrics/picture_score.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/traffic/target_truth.hpp"

namespace skyfuse {

/// The aircraft of `truth` present at step `k`, into `out` (cleared first); in view of the
/// first `stations` stations of `scenario` (each station's detection, or the traffic's).
void aircraft_at_step(const Scenario& scenario, int stations, const std::vector<TargetTruth>& truth,
                      int k, std::vector<TruthPoint>& out);

}  // namespace skyfuse
