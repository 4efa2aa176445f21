#pragma once
// The Monte Carlo's runs for the scenario's motion model, sensor kind and filter: compiled by
// shard of the configuration groups (registry/filter_shards.hpp), each shard in its own
// translation unit per sensor part (configured_runs_shard.cpp, registry/sensor_parts.hpp).

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
/// `Shard` and the sensor of whose first max(station_counts) stations lies in sensor part `Part`.
template <std::size_t Shard, std::size_t Part>
std::vector<RunTrace> simulate_configured_runs_in_shard(const Scenario& scenario,
                                                        const TruthTrajectory& truth,
                                                        std::span<const int> station_counts,
                                                        std::uint64_t run, const NisGate& gate,
                                                        const StepObserver& observer);

}  // namespace skyfuse
