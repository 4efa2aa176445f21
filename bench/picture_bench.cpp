// One station's round of the picture, and the assignment solver alone. Numbers
// printed, never asserted: docs/picture.md quotes them with the command that re-measures
// them (`skyfuse_core_bench --benchmark_filter='PictureStationRound|PicturePredict|Assignment'`).

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "picture_setup.hpp"
#include "skyfuse/association/assignment.hpp"
#include "skyfuse/picture/detection_prior.hpp"

namespace skyfuse {
namespace {

using namespace bench;  // NOLINT: the benchmarks' traffic

constexpr int kStations = 8;
constexpr int kTimedRounds = 20;

// One station's round at N aircraft: its own gating, assignment and increments, then fusing
// every station's reports with management and initiation (what every peer does). The other
// stations' reports and the scans are made outside the timing.
void station_round(benchmark::State& state, int aircraft, const DetectionConfig& detection,
                   const TrackerConfig& tracker = {}) {
  const int steps = kWarmUpSteps + kTimedRounds + 1;
  const auto truths = traffic(aircraft, steps);
  auto stations = radars(aircraft, kStations);
  for (auto& station : stations) {
    station.prior = detection_prior(detection, TrackSensor::kKind, tracker.association);
  }
  Peer peer = warmed_picture(stations, detection, truths, tracker);
  AssociationWork work;
  std::vector<Peer::Report> reports(kStations);
  int k = kWarmUpSteps;
  std::size_t tracks = 0;
  std::size_t largest_cluster = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const auto scans = scans_of(stations, detection, truths, k);
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
    largest_cluster = peer.associate(stations[0], scans[0], work).largest_cluster;
    ++k;
    state.ResumeTiming();
  }
  state.counters["tracks"] = static_cast<double>(tracks);
  state.counters["largest_cluster"] = static_cast<double>(largest_cluster);
}

void BM_PictureStationRound(benchmark::State& state) {
  const int aircraft = static_cast<int>(state.range(0));
  station_round(state, aircraft, detection_for(aircraft));
}
// Arg(1): one aircraft through the picture, against the one-aircraft pipeline's station step
// and fusion (StationStep, FuseIncrements/8 in core_bench.cpp): docs/picture.md, "What
// stays apart, and why".
BENCHMARK(BM_PictureStationRound)
    ->Arg(1)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Iterations(kTimedRounds)
    ->Unit(benchmark::kMillisecond);

// 100 aircraft in 50 false alarms a scan per radar, by each associator: what JPDA's weighing
// of every gated pair costs a station's round against GNN's one detection per track
// (docs/picture.md, "JPDA").
void BM_DenseStationRound(benchmark::State& state, const char* associator) {
  TrackerConfig tracker;
  tracker.association.associator = associator;
  station_round(state, 100, detection_for(100, 0.9, 50.0), tracker);
}
BENCHMARK_CAPTURE(BM_DenseStationRound, gnn, "gnn")
    ->Iterations(kTimedRounds)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DenseStationRound, jpda, "jpda")
    ->Iterations(kTimedRounds)
    ->Unit(benchmark::kMillisecond);

// One aircraft always detected, no false alarm: the single-aircraft runs' setting, through the
// picture. What the picture's own machinery (gating, assignment, initiation's bookkeeping)
// costs where a single-aircraft run needs none of it.
void BM_OneAircraftPictureRoundWithoutClutter(benchmark::State& state) {
  station_round(state, 1, detection_for(1, 1.0, 0.0));
}
BENCHMARK(BM_OneAircraftPictureRoundWithoutClutter)
    ->Iterations(kTimedRounds)
    ->Unit(benchmark::kMicrosecond);

// Predicting every track, which every node does once a round.
void BM_PicturePredict(benchmark::State& state) {
  const int aircraft = static_cast<int>(state.range(0));
  Peer peer(PeerTracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0)),
            radars(aircraft, kStations), TrackerConfig{});
  for (int a = 0; a < aircraft; ++a) {
    peer.add_known_track(make_track_id(0, 0, static_cast<std::uint32_t>(a)),
                         GaussianState<Model::kDim>{});
  }
  for (auto _ : state) {
    peer.predict();
    benchmark::DoNotOptimize(peer.tracks().data());
  }
}
BENCHMARK(BM_PicturePredict)->Arg(1000)->Unit(benchmark::kMicrosecond);

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
