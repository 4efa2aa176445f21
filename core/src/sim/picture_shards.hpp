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

/// How many sensor parts the picture's shards are compiled in (core/CMakeLists.txt says the same):
/// the IMM's peers and center for each sensor kind together made a 1.66 GB file.
inline constexpr std::size_t kPictureSensorParts = 2;

/// run_picture for a scenario whose filter part and motion model lie in shard `Shard` and whose
/// stations' sensor lies in sensor part `Part`; nothing if no picture runs that part on the
/// scenario's model and sensor kind.
template <std::size_t Shard, std::size_t Part>
std::optional<PictureRunResult> run_picture_in_shard(
    const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
    std::uint64_t run, const std::function<void(const PictureStep&)>& on_step);

}  // namespace skyfuse
