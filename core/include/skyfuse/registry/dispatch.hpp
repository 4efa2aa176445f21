#pragma once
/// \file
/// From a scenario's names to code compiled for its types: the sensor kind of its stations
/// and the filter part it names (filter_shards.hpp adds the motion model).

#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// The sensor kind shared by the first `stations` stations; nothing when they differ.
std::optional<std::string> common_sensor_kind(const Scenario& scenario, int stations);

/// Calls f(SensorTemplate<Sensor>{}) for the sensor of the first `stations` stations on an
/// N-entry state: their common sensor, or AnySensor when they differ. The loader has checked
/// every name, so an unknown one here is a programming error and throws std::logic_error.
template <int N, typename F>
void dispatch_sensor(const Scenario& scenario, int stations, F&& f) {
  const std::optional<std::string> sensor_kind = common_sensor_kind(scenario, stations);
  if (!sensor_kind) {
    f(SensorTemplate<AnySensor>{});
  } else if (!visit_sensor_kind<Sensors, N>(*sensor_kind, f)) {
    throw std::logic_error("no registered sensor '" + *sensor_kind + "' for a " +
                           std::to_string(N) + "-entry state");
  }
}

/// Calls f(std::type_identity<Filter>{}) for the registered filter part that runs `filter`: its
/// kind and, for a filter with modes, its modes. The loader has checked that one does, so none
/// here is a programming error and throws std::logic_error.
template <typename F>
void visit_filter(const FilterConfig& filter, F&& f) {
  if (!visit_filter_part<FilterParts>(filter.kind, filter.imm.modes, f)) {
    throw std::logic_error("no registered filter part '" + filter.kind + "' with these modes");
  }
}

}  // namespace skyfuse
