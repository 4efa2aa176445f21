#pragma once
// `skyfuse sweep`: Monte-Carlo runs of both architectures, in-process, for M = 1..M_max stations
// and every speed the scenario lists.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::harness {

struct SweepOptions {
  std::string scenario_path;  ///< empty: the embedded paper000 scenario
  int runs = 50;
  int max_stations = 0;  ///< 0: every station of the scenario
  /// Only the scenario's stations of these ids, in its order; empty: every one.
  std::vector<int> only_stations;
  std::string out_dir = "results/sweep";
  std::optional<std::uint64_t> seed;
  std::optional<int> steps;
  std::optional<ExchangeConfig::Kind> exchange;  ///< default: the scenario's
  std::optional<int> fanout;
  int threads = 0;  ///< 0: one per core
  bool plot = true;
  /// A scenario with recorded traffic: the OpenSky CSV file to run instead of the scenario's.
  std::string traffic_file;
  std::optional<std::string> associator;  ///< default: the scenario's
};

void add_sweep_command(CLI::App& app, SweepOptions& options);
int run_sweep(const SweepOptions& options);

}  // namespace skyfuse::harness
