#pragma once
/// \file
/// A station's systematic errors: what a real sensor adds to every plot besides its noise — a
/// range offset, an azimuth (north-alignment) offset, an elevation offset, a clock offset. The
/// simulator adds them (traffic/scan_simulation.hpp); no filter is told of them, so that a
/// registration has something to estimate. 0.1 degree of azimuth at 100 km moves every plot
/// 175 m, more than the noise a radar's filters are told of.

#include <array>
#include <cstddef>
#include <string_view>

#include "skyfuse/core/types.hpp"

namespace skyfuse {

struct SensorBias {
  /// The measured components a bias offsets, by the names sensors give them (kComponents).
  static constexpr std::array<std::string_view, 3> kComponents = {"range_m", "azimuth_rad",
                                                                  "elevation_rad"};

  double range_m = 0.0;
  double azimuth_rad = 0.0;
  double elevation_rad = 0.0;
  /// The station's clock offset: a plot stamped t was measured at t + time_s.
  double time_s = 0.0;

  bool any() const {
    return range_m != 0.0 || azimuth_rad != 0.0 || elevation_rad != 0.0 || time_s != 0.0;
  }
  /// The offset of the measured component `name`: 0 for one a bias does not offset.
  double of_component(std::string_view name) const {
    if (name == kComponents[0]) return range_m;
    if (name == kComponents[1]) return azimuth_rad;
    if (name == kComponents[2]) return elevation_rad;
    return 0.0;
  }
};

/// The offsets `bias` adds to a detection of `Sensor`, component by component.
template <typename Sensor>
Vector<Sensor::kMeasDim> offsets_of(const SensorBias& bias) {
  Vector<Sensor::kMeasDim> offset;
  for (int i = 0; i < Sensor::kMeasDim; ++i) {
    offset(i) = bias.of_component(Sensor::kComponents[static_cast<std::size_t>(i)]);
  }
  return offset;
}

/// Where the kinematics `x` ([p; v; a], scenario/truth.hpp's kKinematicsDim) put the aircraft
/// `time_s` later (or earlier): the state a station whose clock is off by time_s measures at
/// its stamp.
template <int Dim>
Vector<Dim> kinematics_after(const Vector<Dim>& x, double time_s) {
  static_assert(Dim == 9, "the kinematics [p; v; a]");
  Vector<Dim> later = x;
  later.template head<3>() +=
      time_s * x.template segment<3>(3) + 0.5 * time_s * time_s * x.template tail<3>();
  later.template segment<3>(3) += time_s * x.template tail<3>();
  return later;
}

}  // namespace skyfuse
