#include "skyfuse/sim/picture_detections.hpp"

#include <stdexcept>
#include <string>

#include "skyfuse/picture/fixes_position.hpp"
#include "skyfuse/registry/dispatch.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/traffic_config.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"

namespace skyfuse {

namespace {

// Calls f(sensor, scan, origins) for each of the first `stations` stations' scans at `step`,
// simulated as the stations simulate them (a scan is a function of seed, run, station and step).
template <typename F>
void for_each_scan(const Scenario& scenario, const std::vector<TargetTruth>& truth, int stations,
                   std::uint64_t run, int step, const char* caller, F&& f) {
  if (!scenario.traffic)
    throw std::logic_error(std::string(caller) + ": a scenario with one target");
  // Each station by its own sensor: a picture may mix kinds.
  for (int s = 0; s < stations; ++s) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
    const bool known = visit_sensor_kind<Sensors, kKinematicsDim>(
        station.sensor.kind, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
          using Sensor = SensorOf<kKinematicsDim>;
          if constexpr (FixesPosition<Sensor>) {
            const Sensor sensor = make_sensor<Sensor>(station);
            ScanOrigins origins;
            Scan scan =
                simulate_scan(station.id, sensor, station.position_m,
                              station_noise_covariance<Sensor::kMeasDim>(scenario, station, run),
                              station.detection.value(), truth, step, scenario.seed, run, &origins);
            f(sensor, std::move(scan), std::move(origins));
          } else {
            throw std::logic_error(std::string(caller) + ": a sensor that does not fix a position");
          }
        });
    if (!known) throw std::logic_error(std::string(caller) + ": an unregistered sensor");
  }
}

}  // namespace

std::vector<ScanPositions> scan_positions_at(const Scenario& scenario,
                                             const std::vector<TargetTruth>& truth, int stations,
                                             std::uint64_t run, int step) {
  std::vector<ScanPositions> scans;
  for_each_scan(
      scenario, truth, stations, run, step, "scan_positions_at",
      [&]<typename Sensor>(const Sensor& sensor, Scan scan, ScanOrigins origins) {
        ScanPositions& out = scans.emplace_back();
        out.station_id = scan.station_id;
        out.target = std::move(origins.target);
        for (const auto& detection : scan.detections) {
          out.positions.push_back(sensor.position_of(fixed_detection<Sensor::kMeasDim>(detection)));
        }
      });
  return scans;
}

std::vector<SimulatedScan> simulated_scans_at(const Scenario& scenario,
                                              const std::vector<TargetTruth>& truth, int stations,
                                              std::uint64_t run, int step) {
  std::vector<SimulatedScan> scans;
  for_each_scan(scenario, truth, stations, run, step, "simulated_scans_at",
                [&]<typename Sensor>(const Sensor&, Scan scan, ScanOrigins origins) {
                  scans.push_back({Sensor::kKind, std::move(scan), std::move(origins.target)});
                });
  return scans;
}

}  // namespace skyfuse
