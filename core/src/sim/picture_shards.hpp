#pragma once
// The in-process picture's runs for the scenario's filter part, motion model and sensor kind:
// compiled by shard of the configuration groups (registry/filter_shards.hpp), each shard in
// its own translation unit per sensor part (picture_run_shard.cpp, registry/sensor_parts.hpp).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "skyfuse/sim/picture_run.hpp"

namespace skyfuse {

/// run_picture for a scenario whose filter part and motion model lie in shard `Shard` and whose
/// stations' sensor lies in sensor part `Part`; nothing if no picture runs that part on the
/// scenario's model and sensor kind.
template <std::size_t Shard, std::size_t Part>
std::optional<PictureRunResult> run_picture_in_shard(
    const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
    std::uint64_t run, const std::function<void(const PictureStep&)>& on_step);

}  // namespace skyfuse
