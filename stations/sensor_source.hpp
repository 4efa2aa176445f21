#pragma once
// Where a station's measurements come from: simulated from the scenario and the seed (the same
// functions the in-process sweep calls), or replayed from a CSV file that `skyfuse run` wrote
// (measurements.csv) or that came from a real sensor. A station's sensor is a sensor of the
// truth's kinematic state (TruthSensorOf), whatever state the filter keeps.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::station {

template <typename Sensor>
class SensorSource {
 public:
  using Measurement = Vector<Sensor::kMeasDim>;
  virtual ~SensorSource() = default;
  /// The measurement of `step`, in the sensor's components; throws if there is none.
  virtual Measurement measurement(std::uint64_t step) = 0;
};

[[noreturn]] void throw_no_simulated_step(std::uint64_t step);

template <typename Sensor>
class SimulatedSensor final : public SensorSource<Sensor> {
 public:
  using Measurement = Vector<Sensor::kMeasDim>;
  SimulatedSensor(const RunPlan& plan, const StationConfig& station)
      : truth_(plan.truth()),
        sensor_(make_sensor<TruthSensorOf<Sensor>>(station)),
        noise_(station_noise_covariance<Sensor::kMeasDim>(plan.scenario, station, plan.mc_run)),
        seed_(plan.scenario.seed),
        mc_run_(plan.mc_run),
        station_id_(station.id) {}

  Measurement measurement(std::uint64_t step) override {
    if (step >= truth_.states.size()) throw_no_simulated_step(step);
    return simulate_measurement(sensor_, truth_.states[step], noise_, seed_, mc_run_, station_id_,
                                step);
  }

 private:
  TruthTrajectory truth_;
  TruthSensorOf<Sensor> sensor_;
  Covariance<Sensor::kMeasDim> noise_;
  std::uint64_t seed_;
  std::uint64_t mc_run_;
  int station_id_;
};

/// The rows of station `station_id` in a replay CSV whose header is `step,station_id,` and then
/// `components`; throws std::runtime_error naming the file and the line for anything else, a
/// second row for a step, or a row `reportable` refuses.
std::map<std::uint64_t, std::vector<double>> read_replay_rows(
    const std::filesystem::path& csv, int station_id, const std::vector<std::string>& components,
    bool (*reportable)(const std::vector<double>& values));

[[noreturn]] void throw_no_replayed_step(const std::filesystem::path& csv, std::uint64_t step);

/// CSV with the header `step,station_id,` and the sensor's components (range_azimuth_elevation:
/// `range_m,azimuth_rad,elevation_rad`, as measurements.csv has it); rows of other stations are
/// skipped, so one file can serve every station.
template <typename Sensor>
class ReplayedSensor final : public SensorSource<Sensor> {
 public:
  using Measurement = Vector<Sensor::kMeasDim>;
  ReplayedSensor(const std::filesystem::path& csv, int station_id) : path_(csv) {
    const std::vector<std::string> components(Sensor::kComponents.begin(),
                                              Sensor::kComponents.end());
    for (const auto& [step, values] :
         read_replay_rows(csv, station_id, components, &ReplayedSensor::reportable)) {
      rows_.emplace(step, Measurement(values.data()));
    }
  }

  Measurement measurement(std::uint64_t step) override {
    const auto it = rows_.find(step);
    if (it == rows_.end()) throw_no_replayed_step(path_, step);
    return it->second;
  }

 private:
  static bool reportable(const std::vector<double>& values) {
    return !Sensor::check_reported(Measurement(values.data()));
  }

  std::filesystem::path path_;
  std::map<std::uint64_t, Measurement> rows_;
};

}  // namespace skyfuse::station
