#pragma once
// How a sweep is shown and stored: the console table, sweep.csv, sweep.json and the plot.
// Numbers are printed with fixed formats so that the same seed gives the same bytes.

#include <cstdio>
#include <filesystem>
#include <span>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/monte_carlo.hpp"

namespace skyfuse::harness {

struct SweepReport {
  const Scenario& scenario;
  std::span<const MonteCarloSummary> rows;
};

void print_sweep_table(const SweepReport& report, std::FILE* out);
void write_sweep_csv(const SweepReport& report, const std::filesystem::path& path);
void write_sweep_json(const SweepReport& report, const std::filesystem::path& path);

/// Runs plot_sweep.py (next to the executable) with Debian's python3; false if it failed.
bool plot_sweep(const std::filesystem::path& csv, const std::filesystem::path& png);

}  // namespace skyfuse::harness
