// One shard of the Monte Carlo's runs (registry/filter_shards.hpp): cmake/FilterShards.cmake
// compiles this file once per shard and sensor part (registry/sensor_parts.hpp), with
// SKYFUSE_SHARD and SKYFUSE_SENSOR_PART set.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "sim/configured_runs.hpp"
#include "sim/run_setup.hpp"
#include "sim/run_steppers.hpp"
#include "skyfuse/registry/filter_shards.hpp"
#include "skyfuse/registry/sensor_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"

namespace skyfuse {
namespace {

// One run for each of `station_counts`, all fed from one simulation of the measurements of the
// largest count's stations; a RunStepper or an ImmRunStepper steps each.
template <typename Stepper, template <int> class SensorOf>
std::vector<RunTrace> simulate_runs(const Scenario& scenario, const TruthTrajectory& truth,
                                    std::span<const int> station_counts, std::uint64_t run,
                                    const NisGate& gate, const StepObserver& observer = {}) {
  // The sensors as they see the truth: the target's kinematics, whatever the filter's model.
  using TruthSensor = SensorOf<kKinematicsDim>;
  std::vector<Stepper> steppers;
  steppers.reserve(station_counts.size());
  for (int m : station_counts) steppers.emplace_back(scenario, truth, m, run, gate);
  // Every station of the largest count is simulated, indexed like scenario.stations.
  const auto simulated =
      static_cast<std::size_t>(*std::max_element(station_counts.begin(), station_counts.end()));
  std::vector<ObservationFor<TruthSensor>> truth_sensors;  // sensor and noise per station
  for (std::size_t i = 0; i < simulated; ++i) {
    truth_sensors.push_back(make_observation<TruthSensor>(scenario, scenario.stations[i], run));
  }
  std::vector<typename Stepper::Measurement> z(simulated, Stepper::Measurement::Zero());

  const auto steps = static_cast<std::size_t>(scenario.steps);
  for (std::size_t k = 0; k < steps; ++k) {
    const Vector<kKinematicsDim>& x = truth.states[k];
    for (std::size_t i = 0; i < z.size(); ++i) {
      with_observation(truth_sensors[i], [&](const auto& o) {
        constexpr int kMeasDim = std::decay_t<decltype(o.z)>::RowsAtCompileTime;
        z[i].template head<kMeasDim>() = simulate_measurement(o.sensor, x, o.noise, scenario.seed,
                                                              run, scenario.stations[i].id, k);
      });
    }
    for (Stepper& stepper : steppers) stepper.step(k, x, z, observer);
  }
  std::vector<RunTrace> traces;
  traces.reserve(steppers.size());
  for (Stepper& stepper : steppers) traces.push_back(stepper.take_trace());
  return traces;
}

}  // namespace

template <std::size_t Shard, std::size_t Part>
std::vector<RunTrace> simulate_configured_runs_in_shard(const Scenario& scenario,
                                                        const TruthTrajectory& truth,
                                                        std::span<const int> station_counts,
                                                        std::uint64_t run, const NisGate& gate,
                                                        const StepObserver& observer) {
  std::vector<RunTrace> traces;
  const int most = *std::max_element(station_counts.begin(), station_counts.end());
  visit_group_in_shard<Shard>(scenario.filter, [&]<typename Filter, typename Model>(
                                                   std::type_identity<Filter>,
                                                   std::type_identity<Model>) {
    dispatch_sensor<Model::kDim>(
        scenario, most, [&]<template <int> class SensorOf>(SensorTemplate<SensorOf>) {
          // The caller chose the part by with_sensor_part; the loader allows a filter only on
          // what it runs on.
          if constexpr (!in_sensor_part<SensorOf, Part, kSensorPartsOf<Shard>>) {
            throw std::logic_error(
                fmt::format("sensor part {} of the Monte Carlo's shard {} "
                            "holds no '{}' stations",
                            Part, Shard, scenario.stations.front().sensor.kind));
          } else if constexpr (filter_runs_on<Filter, Model, SensorOf<Model::kDim>>()) {
            using Stepper = typename RunStepperOf<Filter, Model, SensorOf>::type;
            traces = simulate_runs<Stepper, SensorOf>(scenario, truth, station_counts, run, gate,
                                                      observer);
          } else {
            throw std::logic_error(fmt::format("filter {} does not run on {} with these sensors",
                                               Filter::kKind, Model::kKind));
          }
        });
  });
  return traces;
}

template std::vector<RunTrace>
simulate_configured_runs_in_shard<SKYFUSE_SHARD, SKYFUSE_SENSOR_PART>(
    const Scenario& scenario, const TruthTrajectory& truth, std::span<const int> station_counts,
    std::uint64_t run, const NisGate& gate, const StepObserver& observer);

}  // namespace skyfuse
