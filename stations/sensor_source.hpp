#pragma once
// Where a station's measurements come from: simulated from the scenario and the seed (the same
// functions the in-process sweep calls), or replayed from a CSV file that `skyfuse run` wrote
// (measurements.csv) or that came from a real sensor.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>

#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/transport/wire_configuration.hpp"

namespace skyfuse::station {

class SensorSource {
 public:
  virtual ~SensorSource() = default;
  /// The measurement [range m, azimuth rad, elevation rad] of `step`; throws if there is none.
  virtual Vector3 measurement(std::uint64_t step) = 0;
};

class SimulatedSensor final : public SensorSource {
 public:
  SimulatedSensor(const RunPlan& plan, const StationConfig& station);
  Vector3 measurement(std::uint64_t step) override;

 private:
  TruthTrajectory truth_;
  RangeAzimuthElevation<9> sensor_;  // sees the true kinematics
  Covariance<3> noise_;
  std::uint64_t seed_;
  std::uint64_t mc_run_;
  int station_id_;
};

/// CSV with the header `step,station_id,range_m,azimuth_rad,elevation_rad`; rows of other
/// stations are skipped, so one file can serve every station.
class ReplayedSensor final : public SensorSource {
 public:
  ReplayedSensor(const std::filesystem::path& csv, int station_id);
  Vector3 measurement(std::uint64_t step) override;

 private:
  std::filesystem::path path_;
  std::map<std::uint64_t, Vector3> rows_;
};

}  // namespace skyfuse::station
