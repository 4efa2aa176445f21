// One station's round of the multi-target picture, and the assignment solver alone. Numbers
// printed, never asserted: docs/multitarget.md quotes them with the command that re-measures
// them (`skyfuse_core_bench --benchmark_filter='MultiTarget|Assignment'`).

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "skyfuse/association/assignment.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/multitarget/peer_picture.hpp"
#include "skyfuse/multitarget/track_filters.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
using TrackSensor = RangeAzimuthElevation<Model::kDim>;
using TruthSensor = RangeAzimuthElevation<kKinematicsDim>;
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using Peer = PeerPicture<PeerTracks, TrackSensor>;

constexpr int kStations = 8;
constexpr int kWarmUpSteps = 8;  // rounds for every aircraft to get a confirmed track
constexpr int kTimedRounds = 20;

// N aircraft flying straight and level over a square of about one aircraft per km^2.
std::vector<TargetTruth> traffic(int aircraft, int steps) {
  std::mt19937_64 rng(1);
  const double half_side = 500.0 * std::sqrt(static_cast<double>(aircraft));
  std::uniform_real_distribution<double> across(-half_side, half_side);
  std::uniform_real_distribution<double> height(100.0, 600.0);
  std::uniform_real_distribution<double> speed(20.0, 60.0);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::vector<TargetTruth> truths;
  for (int a = 0; a < aircraft; ++a) {
    const Vector3 start(across(rng), across(rng), height(rng));
    const double h = heading(rng);
    const Vector3 velocity = speed(rng) * Vector3(std::cos(h), std::sin(h), 0.0);
    TargetTruth truth{fmt::format("T{}", a), 0, {}};
    for (int k = 0; k < steps; ++k) {
      Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
      x.head<3>() = start + k * velocity;
      x.segment<3>(3) = velocity;
      truth.states.push_back(x);
    }
    truths.push_back(std::move(truth));
  }
  return truths;
}

// M = 8 radars on a circle around the area, seeing all of it.
std::vector<KnownStation<TrackSensor>> radars(int aircraft) {
  const double radius = 700.0 * std::sqrt(static_cast<double>(aircraft)) + 2000.0;
  Covariance<3> noise = Covariance<3>::Zero();
  const double angle_std = 0.05 * std::numbers::pi / 180.0;
  noise.diagonal() << 5.0 * 5.0, angle_std * angle_std, angle_std * angle_std;
  std::vector<KnownStation<TrackSensor>> stations;
  for (int i = 0; i < kStations; ++i) {
    const double bearing = 2.0 * std::numbers::pi * i / kStations;
    const Vector3 site(radius * std::cos(bearing), radius * std::sin(bearing), 30.0);
    stations.push_back({i + 1, TrackSensor(site), noise, 1.0});
  }
  return stations;
}

// One station's round at N aircraft: its own gating, assignment and increments, then fusing
// every station's reports with management and initiation (what every peer does). The other
// stations' reports and the scans are made outside the timing.
void BM_MultiTargetStationRound(benchmark::State& state) {
  const int aircraft = static_cast<int>(state.range(0));
  const int steps = kWarmUpSteps + kTimedRounds + 1;
  const auto truths = traffic(aircraft, steps);
  const auto stations = radars(aircraft);
  DetectionConfig detection;
  detection.probability = 0.9;
  detection.field_of_view.max_range_m = 4.0 * (700.0 * std::sqrt(aircraft) + 2000.0);
  detection.field_of_view.min_elevation_rad = 0.0;
  detection.clutter_per_scan = 10.0;
  Peer peer(PeerTracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0)), stations,
            TrackerConfig{});
  AssignmentWork work;
  std::vector<Peer::Report> reports(kStations);
  int k = 0;
  auto scans_of = [&](int step) {
    std::vector<Scan<3>> scans;
    for (const auto& s : stations) {
      scans.push_back(simulate_scan(s.id, TruthSensor(s.sensor.site()), s.sensor.site(), s.noise,
                                    detection, truths, step, 7, 0));
    }
    return scans;
  };
  for (; k < kWarmUpSteps; ++k) {
    const auto scans = scans_of(k);
    peer.predict();
    for (int s = 0; s < kStations; ++s) {
      reports[s] = peer.report(stations[s], scans[s], work);
    }
    peer.fuse(static_cast<std::uint64_t>(k), reports);
  }
  std::size_t tracks = 0;
  std::size_t largest_cluster = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const auto scans = scans_of(k);
    peer.predict();  // every node does it; timed apart below
    for (int s = 1; s < kStations; ++s) {
      reports[s] = peer.report(stations[s], scans[s], work);
    }
    state.ResumeTiming();
    reports[0] = peer.report(stations[0], scans[0], work);
    peer.fuse(static_cast<std::uint64_t>(k), reports);
    benchmark::DoNotOptimize(peer.tracks().data());
    state.PauseTiming();
    tracks = peer.tracks().size();
    const auto assignment =
        assign_scan(peer.estimates(), stations[0].sensor, scans[0], peer.gate(), 4096, work);
    largest_cluster = assignment.largest_cluster;
    ++k;
    state.ResumeTiming();
  }
  state.counters["tracks"] = static_cast<double>(tracks);
  state.counters["largest_cluster"] = static_cast<double>(largest_cluster);
}
BENCHMARK(BM_MultiTargetStationRound)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Iterations(kTimedRounds)
    ->Unit(benchmark::kMillisecond);

// Predicting every track, which every node does once a round.
void BM_MultiTargetPredict(benchmark::State& state) {
  const int aircraft = static_cast<int>(state.range(0));
  Peer peer(PeerTracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0)),
            radars(aircraft), TrackerConfig{});
  for (int a = 0; a < aircraft; ++a) {
    peer.add_known_track(make_track_id(0, 0, static_cast<std::uint32_t>(a)),
                         GaussianState<Model::kDim>{});
  }
  for (auto _ : state) {
    peer.predict();
    benchmark::DoNotOptimize(peer.tracks().data());
  }
}
BENCHMARK(BM_MultiTargetPredict)->Arg(1000)->Unit(benchmark::kMicrosecond);

// The dense solver on an n x n problem of uniform costs: its worst case, as no gate splits it.
void BM_AssignmentDense(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> cost(0.0, 100.0);
  association::CostMatrix costs(n, n);
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t c = 0; c < n; ++c) costs(r, c) = cost(rng);
  }
  for (auto _ : state) benchmark::DoNotOptimize(association::solve_assignment(costs));
}
BENCHMARK(BM_AssignmentDense)->RangeMultiplier(10)->Range(10, 1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace skyfuse
