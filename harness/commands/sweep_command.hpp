#pragma once
// `skyfuse sweep`: Monte-Carlo runs of both architectures, in-process, for M = 1..M_max stations
// and every speed the scenario lists.

#include <CLI/App.hpp>
#include <string>

#include "skyfuse/sim/sweep_plan.hpp"

namespace skyfuse::harness {

struct SweepOptions {
  std::string scenario_path;  ///< empty: the embedded paper000 scenario
  int runs = 50;
  std::string out_dir = "results/sweep";
  int threads = 0;  ///< 0: one per core
  bool plot = true;
  /// What the sweep changes of its scenario, as its plan takes it (sim/sweep_plan.hpp).
  SweepOverrides overrides;
};

void add_sweep_command(CLI::App& app, SweepOptions& options);
int run_sweep(const SweepOptions& options);

}  // namespace skyfuse::harness
