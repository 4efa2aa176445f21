// Cost of the per-step work of each architecture:
//   StationStep      one station's predict + measurement model + information increment
//   UnscentedStationStep   the same with the unscented filter's increment (sigma points of the
//                    prior, each through the sensor, the regression H~)
//   FuseIncrements   one peer fusing M increments into the common prior
//   StackedEkf       the fusion center's stacked update over M measurements
//   CheckIncrement / CheckObservation   a receiver's checks of one sample before fusing it
// Problems are built from the default scenario's geometry so the numbers mean something.
#include <benchmark/benchmark.h>

#include <vector>

#include "skyfuse/fusion/increment_fusion.hpp"
#include "skyfuse/fusion/stacked_ekf.hpp"
#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/scenario/truth.hpp"
#include "skyfuse/tracking/increment_rules_impl.hpp"
#include "skyfuse/tracking/peer_tracker.hpp"
#include "skyfuse/validation/sample_checks.hpp"

namespace skyfuse {
namespace {

// A converged prior and M stations' measurements at one instant of the default scenario.
struct Snapshot {
  GaussianState<9> prior;
  std::vector<StationObservation<RangeAzimuthElevation<9>>> observations;
  std::vector<InformationIncrement<9>> increments;
  std::vector<double> weights;
};

Snapshot make_snapshot(int stations) {
  const Scenario scenario = load_default_scenario();
  const TruthTrajectory truth =
      generate_truth(scenario.target, scenario.target.speeds_mps[0], scenario.time_step_s, 500);
  const Vector<9>& x = truth.states[500];
  Snapshot s;
  s.prior.mean = x;
  s.prior.covariance = 0.05 * Covariance<9>::Identity();
  for (int i = 0; i < stations; ++i) {
    // Beyond the scenario's ten stations, reuse their sites with new ids.
    const StationConfig& site =
        scenario.stations[static_cast<std::size_t>(i) % scenario.stations.size()];
    StationObservation<RangeAzimuthElevation<9>> obs;
    obs.station_id = i + 1;
    obs.sensor = RangeAzimuthElevation<9>(site.position_m + Vector3(0.0, 0.0, i / 10));
    obs.noise = station_noise_covariance<3>(scenario, site, 0);
    obs.z = simulate_measurement(obs.sensor, x, obs.noise, 1, 0, i + 1, 500);
    s.observations.push_back(obs);
    s.increments.emplace_back();
    compute_increment(obs.station_id, s.prior, obs.sensor, obs.z, obs.noise, s.increments.back());
    s.weights.push_back(1.0);
  }
  return s;
}

// One station's step with the increment rule `Rule` (tracking/increment_rules.hpp): predict,
// then its own measurement's increment against the predicted prior.
template <typename Rule>
void StationStepWith(benchmark::State& state) {
  const Snapshot s = make_snapshot(1);
  const Scenario scenario = load_default_scenario();
  const auto motion = make_motion_model<ConstantAcceleration3D>(scenario);
  PeerTracker tracker(motion, s.prior);
  const auto& obs = s.observations.front();
  InformationIncrement<9> increment;
  for (auto _ : state) {
    tracker.predict();
    benchmark::DoNotOptimize(Rule::contribute(tracker.estimate(), obs, NisGate{}, increment));
    benchmark::DoNotOptimize(increment);
  }
}
void StationStep(benchmark::State& state) {
  StationStepWith<EkfIncrementRule>(state);
}
BENCHMARK(StationStep);
void UnscentedStationStep(benchmark::State& state) {
  StationStepWith<UnscentedIncrementRule>(state);
}
BENCHMARK(UnscentedStationStep);

void CheckIncrement(benchmark::State& state) {
  const Snapshot s = make_snapshot(1);
  for (auto _ : state) benchmark::DoNotOptimize(check_increment(s.increments.front()));
}
BENCHMARK(CheckIncrement);

void CheckObservation(benchmark::State& state) {
  const Snapshot s = make_snapshot(1);
  for (auto _ : state) benchmark::DoNotOptimize(check_observation(s.observations.front()));
}
BENCHMARK(CheckObservation);

void Predict(benchmark::State& state) {
  const Scenario scenario = load_default_scenario();
  const auto motion = make_motion_model<ConstantAcceleration3D>(scenario);
  const GaussianState<9> start = make_snapshot(1).prior;
  GaussianState<9> s = start;
  for (auto _ : state) {
    s.covariance = start.covariance;  // keep P bounded: the cost must not drift with its size
    predict(s, motion);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(Predict);

void FuseIncrements(benchmark::State& state) {
  const Snapshot s = make_snapshot(static_cast<int>(state.range(0)));
  GaussianState<9> posterior;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fuse_increments<9>(s.prior, s.increments, s.weights, posterior));
    benchmark::DoNotOptimize(posterior);
  }
  state.counters["M"] = static_cast<double>(state.range(0));
}
BENCHMARK(FuseIncrements)->RangeMultiplier(2)->Range(1, 128);

void StackedEkfUpdate(benchmark::State& state) {
  const Snapshot s = make_snapshot(static_cast<int>(state.range(0)));
  StackedEkf<9, RangeAzimuthElevation<9>> stacked;
  GaussianState<9> posterior;
  for (auto _ : state) {
    posterior = s.prior;
    benchmark::DoNotOptimize(stacked.update(posterior, s.observations));
    benchmark::DoNotOptimize(posterior);
  }
  state.counters["M"] = static_cast<double>(state.range(0));
}
BENCHMARK(StackedEkfUpdate)->RangeMultiplier(2)->Range(1, 128);

}  // namespace
}  // namespace skyfuse

BENCHMARK_MAIN();
