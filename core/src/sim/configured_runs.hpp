#pragma once
// The Monte Carlo's runs for the scenario's motion model, sensor kind and filter: compiled by
// shard of the configuration groups (registry/filter_shards.hpp), each shard in its own
// translation unit (configured_runs_shard.cpp).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/validation/nis_gate.hpp"

namespace skyfuse {

/// One run for each of `station_counts`, all fed from one simulation of the measurements of the
/// largest count's stations, for a scenario whose filter part and motion model lie in shard
/// `Shard`.
template <std::size_t Shard>
std::vector<RunTrace> simulate_configured_runs_in_shard(const Scenario& scenario,
                                                        const TruthTrajectory& truth,
                                                        std::span<const int> station_counts,
                                                        std::uint64_t run, const NisGate& gate,
                                                        const StepObserver& observer);

}  // namespace skyfuse
