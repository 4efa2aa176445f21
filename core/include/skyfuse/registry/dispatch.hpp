#pragma once
/// \file
/// From a scenario's names to code compiled for its types: the motion model it names and the
/// sensor kind of its stations.

#include <stdexcept>
#include <string>
#include <type_traits>

#include "skyfuse/registry/registry.hpp"
#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse {

/// The sensor kind shared by the first `stations` stations; std::invalid_argument naming the
/// kinds when they differ.
std::string common_sensor_kind(const Scenario& scenario, int stations);

/// Calls f(std::type_identity<Model>{}, SensorTemplate<Sensor>{}) for the scenario's motion
/// model and the sensor kind of its first `stations` stations, which must all have the same
/// kind. The loader has checked every name, so an unknown one here is a programming error and
/// throws std::logic_error.
template <typename F>
void dispatch_configuration(const Scenario& scenario, int stations, F&& f) {
  const std::string sensor_kind = common_sensor_kind(scenario, stations);
  bool sensor_found = false;
  const bool model_found = visit_model_kind<MotionModels>(
      scenario.filter.motion_model.kind, [&]<typename Model>(std::type_identity<Model> model) {
        sensor_found = visit_sensor_kind<Sensors, Model::kDim>(
            sensor_kind, [&](auto sensor) { f(model, sensor); });
      });
  if (!model_found || !sensor_found) {
    throw std::logic_error("no registered configuration for motion model '" +
                           scenario.filter.motion_model.kind + "' with sensor '" + sensor_kind +
                           "'");
  }
}

}  // namespace skyfuse
