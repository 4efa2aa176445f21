#pragma once
/// \file
/// The participants of a run with many aircraft as every node knows them: each station's id,
/// sensor, noise, weight and detection prior, the same bits in every process and in the in-process
/// run.

#include <cstdint>
#include <vector>

#include "skyfuse/multitarget/detection_prior.hpp"
#include "skyfuse/multitarget/track_table.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse {

/// The first `stations` stations of `scenario` with sensors of type `Sensor`, their noise that
/// of Monte-Carlo run `run`.
template <typename Sensor>
std::vector<KnownStation<Sensor>> known_stations(const Scenario& scenario, int stations,
                                                 std::uint64_t run) {
  std::vector<KnownStation<Sensor>> known;
  for (int s = 0; s < stations; ++s) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
    known.push_back({station.id, make_sensor<Sensor>(station),
                     station_noise_covariance<Sensor::kMeasDim>(scenario, station, run),
                     station.weight,
                     detection_prior(station.detection.value(), station.sensor.kind,
                                     scenario.tracker.association)});
  }
  return known;
}

}  // namespace skyfuse
