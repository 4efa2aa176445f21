#pragma once
// `skyfuse bench`: what the system costs on this machine, in one command.
//   1. micro-benchmarks of the core (station step, fusion of M increments, stacked EKF update)
//      from the Google Benchmark binary beside this one;
//   2. for each station count M: the bare Fast DDS lock-step floor (one commander, M echo
//      processes, the same participant setup and QoS) and then a real lock-step run with M
//      station processes and the center, back to back so that both see the same machine load.
// Writes bench.json and prints the table the README quotes. With --scale, the scale benchmark
// instead (scale_bench.hpp).

#include <CLI/App.hpp>
#include <string>
#include <vector>

#include "scale/scale_bench.hpp"

namespace skyfuse::harness {

struct BenchOptions {
  std::string out_dir = "results/bench";
  std::string scenario_path;  ///< default: scenarios/ring64.yaml beside the executable
  std::vector<int> stations = {1, 2, 4, 8, 16, 32, 64};
  int rounds = 300;
  int domain = 0;
  bool micro = true;
  /// --scale: the scale benchmark, with --out, --scenario, --stations, --rounds and --domain
  /// copied in when given.
  bool scale_requested = false;
  ScaleBenchOptions scale;
};

void add_bench_command(CLI::App& app, BenchOptions& options);
int run_bench(const BenchOptions& options);

}  // namespace skyfuse::harness
