#pragma once
// The in-process picture's runs for the scenario's filter part and motion model: compiled by
// shard of the configuration groups (registry/filter_shards.hpp), each shard in its own
// translation unit (picture_run_shard.cpp); the stations' sensors are values.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "skyfuse/sim/picture_run.hpp"

namespace skyfuse {

/// run_picture for a scenario whose filter part and motion model lie in shard `Shard`; nothing
/// if no picture runs that part on the scenario's model.
template <std::size_t Shard>
std::optional<PictureRunResult> run_picture_in_shard(
    const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
    std::uint64_t run, const std::function<void(const PictureStep&)>& on_step,
    const ScanFilter& scan_filter);

}  // namespace skyfuse
