#pragma once
/// \file
/// The heights a sensor that cannot place an aircraft in height (a 2-D radar,
/// range_azimuth.hpp) assumes it flies at: a band from the scenario, taken as uniform.

namespace skyfuse {

struct HeightBand {
  double low_m = 0.0;   ///< world frame, m
  double high_m = 0.0;  ///< above low_m

  double middle_m() const { return 0.5 * (low_m + high_m); }
  /// The variance of a height uniform over the band, m^2.
  double variance_m2() const { return (high_m - low_m) * (high_m - low_m) / 12.0; }
};

}  // namespace skyfuse
