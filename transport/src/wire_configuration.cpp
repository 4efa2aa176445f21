#include "skyfuse/transport/wire_configuration.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace skyfuse::transport {

void require_wire_configuration(const Scenario& scenario, int stations) {
  if (scenario.filter.motion_model.kind != WireModel::kKind) {
    throw std::invalid_argument(fmt::format(
        "scenario '{}': motion model {}: the station and center processes run {} only for now; "
        "other models run in-process",
        scenario.name, scenario.filter.motion_model.kind, WireModel::kKind));
  }
  for (int i = 0; i < stations; ++i) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(i)];
    if (station.sensor.kind != WireSensor::kKind) {
      throw std::invalid_argument(fmt::format(
          "scenario '{}': station {} has a {} sensor: the station and center processes carry {} "
          "sensors only for now; other sensors run in-process",
          scenario.name, station.id, station.sensor.kind, WireSensor::kKind));
    }
  }
}

}  // namespace skyfuse::transport
