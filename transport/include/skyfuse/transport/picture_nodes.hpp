#pragma once
/// \file
/// What the station and center processes of a run with many aircraft share: the filter they run
/// over DDS so far and the sensor type the run's stations have. The in-process run (`skyfuse
/// sweep`) runs every registered filter part; over DDS it is the EKF on constant velocity until
/// the others are compiled for the processes too.

#include <fmt/format.h>

#include <stdexcept>

#include "skyfuse/filters/parts/ekf_part.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/multitarget/fixes_position.hpp"
#include "skyfuse/registry/registry.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"

namespace skyfuse::transport {

using PictureModel = ConstantVelocity3D;

/// Calls f(std::type_identity<Sensor>{}) with the sensor type of `plan`'s stations (every one
/// of one kind, one detection of which fixes a position: the loader checked), after refusing a
/// filter the processes do not run yet. Returns what f returns.
template <typename F>
int with_picture_sensor(const PicturePlan& plan, F&& f) {
  const FilterConfig& filter = plan.scenario.filter;
  if (filter.kind != EkfFilterPart::kKind || filter.motion_model.kind != PictureModel::kKind) {
    throw std::invalid_argument(fmt::format(
        "scenario '{}': over DDS a run of many aircraft runs the EKF on constant velocity so "
        "far, not '{}' on '{}' (`skyfuse sweep` runs it in-process)",
        plan.scenario.name, filter.kind, filter.motion_model.kind));
  }
  int code = 1;
  const bool known = visit_sensor_kind<Sensors, PictureModel::kDim>(
      plan.scenario.stations.front().sensor.kind,
      [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
        using Sensor = SensorOf<PictureModel::kDim>;
        if constexpr (FixesPosition<Sensor>) {
          code = f(std::type_identity<Sensor>{});
        } else {
          throw std::invalid_argument(
              fmt::format("sensor '{}': a run of many aircraft takes sensors one detection of "
                          "which fixes a position",
                          Sensor::kKind));
        }
      });
  if (!known) throw std::logic_error("a picture node: unknown sensor kind");
  return code;
}

}  // namespace skyfuse::transport
