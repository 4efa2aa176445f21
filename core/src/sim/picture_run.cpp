#include "skyfuse/sim/picture_run.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "sim/picture_shards.hpp"
#include "skyfuse/registry/filter_shards.hpp"

namespace skyfuse {

PictureRunResult run_picture(const Scenario& scenario, const std::vector<TargetTruth>& truth,
                             int stations, std::uint64_t run,
                             const std::function<void(const PictureStep&)>& on_step,
                             const ScanFilter& scan_filter) {
  if (!scenario.traffic) throw std::logic_error("run_picture: a scenario with one target");
  if (stations < 1 || stations > static_cast<int>(scenario.stations.size())) {
    throw std::invalid_argument(
        fmt::format("run_picture: {} stations of {}", stations, scenario.stations.size()));
  }
  const auto result = with_filter_shard(scenario.filter, [&](auto shard) {
    return run_picture_in_shard<decltype(shard)::value>(scenario, truth, stations, run, on_step,
                                                        scan_filter);
  });
  if (!result) {
    throw std::logic_error(fmt::format(
        "run_picture: no picture for filter '{}' on '{}' with {} stations (the loader refuses "
        "these)",
        scenario.filter.kind, scenario.filter.motion_model.kind,
        scenario.stations.front().sensor.kind));
  }
  return *result;
}

}  // namespace skyfuse
