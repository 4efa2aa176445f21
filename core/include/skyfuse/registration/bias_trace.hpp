#pragma once
/// \file
/// One station's registration over a run: its estimated biases and their standard deviations
/// after each round, beside the biases it truly has (the scenario's, unknown to every filter),
/// and what a reader asks of them: is every estimate within 2σ of its truth, and from which
/// round on does it stay so.

#include <array>
#include <vector>

#include "skyfuse/traffic/sensor_bias.hpp"

namespace skyfuse {

struct BiasTrace {
  /// The entries of SensorBias (range, azimuth, elevation, clock), in that order.
  static constexpr std::array<const char*, 4> kEntries = {"range_m", "azimuth_rad", "elevation_rad",
                                                          "time_s"};

  int station_id = 0;
  /// Which entries the station's estimate holds (StationBias::estimated).
  std::array<bool, 4> estimated{};
  SensorBias truth;
  /// After each round, as settled for the next: the estimate and its standard deviations.
  std::vector<SensorBias> estimate;
  std::vector<SensorBias> sigma;
};

/// Entry `entry` (BiasTrace::kEntries' order) of `bias`.
double bias_entry(const SensorBias& bias, std::size_t entry);

/// Whether every entry the station estimates is within `sigmas` standard deviations of its
/// truth after round `round`.
bool within_sigmas(const BiasTrace& trace, std::size_t round, double sigmas);

/// The first round from which every estimated entry stays within `sigmas` of its truth to the
/// end of the trace; -1 where the last round's is not.
int converged_from(const BiasTrace& trace, double sigmas);

}  // namespace skyfuse
