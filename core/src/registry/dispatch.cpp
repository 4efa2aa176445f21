#include "skyfuse/registry/dispatch.hpp"

#include <fmt/format.h>

namespace skyfuse {

std::string common_sensor_kind(const Scenario& scenario, int stations) {
  const std::string& first = scenario.stations.front().sensor.kind;
  for (int i = 1; i < stations; ++i) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(i)];
    if (station.sensor.kind != first) {
      throw std::invalid_argument(fmt::format(
          "scenario '{}': station {} has a {} sensor, station {} a {} sensor; a run with mixed "
          "sensor kinds is not supported yet",
          scenario.name, scenario.stations.front().id, first, station.id, station.sensor.kind));
    }
  }
  return first;
}

}  // namespace skyfuse
