#pragma once
/// \file
/// The participants of a run with many aircraft as every node knows them: each station's id,
/// sensor, noise, weight and detection prior, the same bits in every process and in the in-process
/// run.

#include <cstdint>
#include <variant>
#include <vector>

#include "skyfuse/picture/detection_prior.hpp"
#include "skyfuse/picture/track_table.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/scenario/traffic_config.hpp"

namespace skyfuse {

/// The first `stations` stations of `scenario`, each with its sensor for the tracks' N-entry
/// state, their noise that of Monte-Carlo run `run`.
template <int N>
std::vector<KnownStation<N>> known_stations(const Scenario& scenario, int stations,
                                            std::uint64_t run) {
  std::vector<KnownStation<N>> known;
  for (int s = 0; s < stations; ++s) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
    PictureSensor<N> sensor = make_picture_sensor<N>(station);
    const DetectionNoise noise = std::visit(
        [&]<typename Sensor>(const Sensor& /*sensor*/) {
          return DetectionNoise(station_noise_covariance<Sensor::kMeasDim>(scenario, station, run));
        },
        sensor);
    known.push_back({station.id, std::move(sensor), noise, station.weight,
                     detection_prior(station.detection.value(), station.sensor.kind,
                                     scenario.tracker.association)});
  }
  return known;
}

}  // namespace skyfuse
