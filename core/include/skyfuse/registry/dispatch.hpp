#pragma once
/// \file
/// From a scenario's names to code compiled for its types: the motion model it names and the
/// sensor kind of its stations.

#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// The sensor kind shared by the first `stations` stations; nothing when they differ.
std::optional<std::string> common_sensor_kind(const Scenario& scenario, int stations);

/// Calls f(std::type_identity<Model>{}, SensorTemplate<Sensor>{}) for the scenario's motion
/// model and the sensor of its first `stations` stations: their common sensor, or AnySensor
/// when they differ. The loader has checked every name, so an unknown one here is a programming
/// error and throws std::logic_error.
template <typename F>
void dispatch_configuration(const Scenario& scenario, int stations, F&& f) {
  const std::optional<std::string> sensor_kind = common_sensor_kind(scenario, stations);
  bool sensor_found = false;
  const bool model_found = visit_model_kind<MotionModels>(
      scenario.filter.motion_model.kind, [&]<typename Model>(std::type_identity<Model> model) {
        if (!sensor_kind) {
          f(model, SensorTemplate<AnySensor>{});
          sensor_found = true;
          return;
        }
        sensor_found = visit_sensor_kind<Sensors, Model::kDim>(
            *sensor_kind, [&](auto sensor) { f(model, sensor); });
      });
  if (!model_found || !sensor_found) {
    throw std::logic_error("no registered configuration for motion model '" +
                           scenario.filter.motion_model.kind + "' with sensor '" +
                           sensor_kind.value_or("(mixed)") + "'");
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
