#pragma once
/// \file
/// The heights a sensor that cannot place an aircraft in height (a 2-D radar,
/// range_azimuth.hpp) assumes it flies at: a band from the scenario, taken as uniform.

#include <concepts>

namespace skyfuse {

struct HeightBand {
  double low_m = 0.0;   ///< world frame, m
  double high_m = 0.0;  ///< above low_m

  double middle_m() const { return 0.5 * (low_m + high_m); }
  /// The variance of a height uniform over the band, m^2.
  double variance_m2() const { return (high_m - low_m) * (high_m - low_m) / 12.0; }
};

/// A sensor that measures no height: the scenario gives the band it assumes
/// (`sensor.height_band_m`), the sensor is built with it and keeps it.
template <typename Sensor>
concept TakesHeightBand = Sensor::kAssumesHeight && requires(const Sensor& sensor) {
  { sensor.height_band() } -> std::convertible_to<HeightBand>;
};

}  // namespace skyfuse
