#pragma once
// `skyfuse bench --scale`: what a round costs as the station count grows, for the flat and the
// tree exchange side by side, for either kind of run. For each configuration, a lock-step run
// and a real-time run at the scenario's step, with what the house measures of both (rounds/s,
// UDP datagrams received per round as the kernel counts them, CPU per station-round, peak
// memory of a node, discovery time) and the kind's own columns:
// - one aircraft (for each M and exchange): latency, the data samples a round must deliver
//   against the datagrams, the share of real-time rounds with every input in time and the
//   track age; counts past what one host's ports hold run on simulated hosts (`skyfuse run
//   --hosts`, root only). Writes scale.json, scale.csv and scale.png.
// - many aircraft (`--aircraft N...`, for each N, M and exchange): the pictures' agreement and
//   the share of real-time rounds with every scan fused in time. Writes picture_scale.json and
//   picture_scale.csv.
// The rows are rewritten after each run, so a stopped bench keeps what it measured.

#include <string>
#include <vector>

#include "skyfuse/options/network_options.hpp"

namespace skyfuse::harness {

struct ScaleBenchOptions {
  std::string out_dir = "results/scale";
  std::string scenario_path;  ///< default: scenarios/ring256.yaml beside the executable
  std::vector<int> stations = {4, 8, 16, 32, 64};
  std::vector<std::string> exchanges = {"flat", "tree"};
  int fanout = 8;
  int rounds = 300;          ///< lock-step rounds per run
  int realtime_steps = 500;  ///< real-time steps per run; 0 skips the real-time runs
  double realtime_deadline_ms = 15.0;
  bool best_effort = true;  ///< increments, partial sums and measurements BEST_EFFORT
  /// Runs on simulated hosts discover their exchange partners only (`--discovery peers`): on 2
  /// cores, M = 128 on 4 hosts matched in 11.5 s that way, in 127 s by multicast, and the
  /// server's Fast DDS 2.9 dropped endpoints for good (docs/performance.md#m--128-and-m--256).
  options::Discovery host_discovery = options::Discovery::kPeers;
  int domain = 0;
  /// Stations per station process (`skyfuse run --stations-per-process`); 1: one process each.
  int stations_per_process = 1;
  /// Numbers of aircraft: the bench of a picture (a scenario with traffic) instead.
  std::vector<int> aircraft;
};

int run_scale_bench(const ScaleBenchOptions& options);

}  // namespace skyfuse::harness
