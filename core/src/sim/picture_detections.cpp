#include "skyfuse/sim/picture_detections.hpp"

#include <stdexcept>

#include "skyfuse/picture/fixes_position.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"

namespace skyfuse {

std::vector<ScanPositions> scan_positions_at(const Scenario& scenario,
                                             const std::vector<TargetTruth>& truth, int stations,
                                             std::uint64_t run, int step) {
  if (!scenario.traffic) throw std::logic_error("scan_positions_at: a scenario with one target");
  std::vector<ScanPositions> scans;
  // Each station by its own sensor: a picture may mix kinds.
  for (int s = 0; s < stations; ++s) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
    const bool known = visit_sensor_kind<Sensors, kKinematicsDim>(
        station.sensor.kind, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
          using Sensor = SensorOf<kKinematicsDim>;
          if constexpr (FixesPosition<Sensor>) {
            const Sensor sensor = make_sensor<Sensor>(station);
            ScanOrigins origins;
            const auto scan =
                simulate_scan(station.id, sensor, station.position_m,
                              station_noise_covariance<Sensor::kMeasDim>(scenario, station, run),
                              station.detection.value(), truth, step, scenario.seed, run, &origins);
            ScanPositions& out = scans.emplace_back();
            out.station_id = station.id;
            out.target = std::move(origins.target);
            for (const auto& detection : scan.detections) {
              out.positions.push_back(
                  sensor.position_of(fixed_detection<Sensor::kMeasDim>(detection)));
            }
          } else {
            throw std::logic_error("scan_positions_at: a sensor that does not fix a position");
          }
        });
    if (!known) throw std::logic_error("scan_positions_at: an unregistered sensor");
  }
  return scans;
}

}  // namespace skyfuse
