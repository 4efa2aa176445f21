#include "skyfuse/registry/dispatch.hpp"

namespace skyfuse {

std::optional<std::string> common_sensor_kind(const Scenario& scenario, int stations) {
  const std::string& first = scenario.stations.front().sensor.kind;
  for (int i = 1; i < stations; ++i) {
    if (scenario.stations[static_cast<std::size_t>(i)].sensor.kind != first) return std::nullopt;
  }
  return first;
}

}  // namespace skyfuse
