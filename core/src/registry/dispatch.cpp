#include "skyfuse/registry/dispatch.hpp"

#include <algorithm>

#include "skyfuse/registry/part_info.hpp"
#include "skyfuse/registry/sensor_parts.hpp"

namespace skyfuse {

std::optional<std::string> common_sensor_kind(const Scenario& scenario, int stations) {
  const std::string& first = scenario.stations.front().sensor.kind;
  for (int i = 1; i < stations; ++i) {
    if (scenario.stations[static_cast<std::size_t>(i)].sensor.kind != first) return std::nullopt;
  }
  return first;
}

std::size_t sensor_slot(const Scenario& scenario, int stations) {
  const std::vector<SensorInfo> sensors = sensor_infos();
  const std::optional<std::string> kind = common_sensor_kind(scenario, stations);
  if (!kind) return sensors.size();
  const auto found = std::ranges::find(sensors, std::string_view(*kind), &SensorInfo::kind);
  return static_cast<std::size_t>(found - sensors.begin());
}

}  // namespace skyfuse
