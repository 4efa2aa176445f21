#pragma once
/// \file
/// Sensors one of whose detections fixes a position (a radar's range, azimuth and elevation; a
/// position fix): a track can start from one, so a run with many aircraft takes them, and only
/// them. A sensor says so by having position_of(z).

#include <concepts>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

template <typename Sensor>
concept FixesPosition = requires(const Sensor& sensor, const typename Sensor::Measurement& z) {
  { sensor.position_of(z) } -> std::convertible_to<Vector3>;
};

}  // namespace skyfuse
