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
  /// The offset of kComponents[component].
  double offset(std::size_t component) const {
    return component == 0 ? range_m : component == 1 ? azimuth_rad : elevation_rad;
  }
  void set_offset(std::size_t component, double value) {
    (component == 0 ? range_m : component == 1 ? azimuth_rad : elevation_rad) = value;
  }
};

/// Which of SensorBias's offsets (its kComponents index) reaches each of `Sensor`'s measured
/// components, in the sensor's order; -1 where none does. The one table every mapping between
/// a sensor's components and a bias reads.
template <typename Sensor>
constexpr std::array<int, Sensor::kMeasDim> bias_components_of() {
  std::array<int, Sensor::kMeasDim> index{};
  for (std::size_t i = 0; i < index.size(); ++i) {
    index[i] = -1;
    for (std::size_t c = 0; c < SensorBias::kComponents.size(); ++c) {
      if (Sensor::kComponents[i] == SensorBias::kComponents[c]) index[i] = static_cast<int>(c);
    }
  }
  return index;
}

/// The offsets `bias` adds to a detection of `Sensor`, component by component.
template <typename Sensor>
Vector<Sensor::kMeasDim> offsets_of(const SensorBias& bias) {
  constexpr auto components = bias_components_of<Sensor>();
  Vector<Sensor::kMeasDim> offset;
  for (int i = 0; i < Sensor::kMeasDim; ++i) {
    const int c = components[static_cast<std::size_t>(i)];
    offset(i) = c < 0 ? 0.0 : bias.offset(static_cast<std::size_t>(c));
  }
  return offset;
}

/// Where the kinematics `x` ([p; v; a], scenario/truth.hpp's kKinematicsDim) put the aircraft
/// `time_s` later (or earlier): the state a station whose clock is off by time_s measures at
/// its stamp. A template on the size only because this header cannot include truth.hpp (which
/// includes the station configuration that includes this file).
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
