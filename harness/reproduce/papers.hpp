#pragma once
// The papers `skyfuse reproduce` knows, each run in-process with the core's filters.

#include <cstdint>
#include <filesystem>
#include <optional>

#include "reproduce/claims.hpp"

namespace skyfuse::harness {

struct ReproduceSettings {
  std::optional<int> runs;            ///< default: the paper's
  std::optional<std::uint64_t> seed;  ///< default: the scenario's or the experiment's
  std::filesystem::path out_dir;      ///< CSV, PNG and reproduce.json go here
  int threads = 0;                    ///< 0: one per core
  bool plot = true;
  /// Where shipped data lives (paper 001's trained weights under paper001/).
  std::filesystem::path data_dir;
};

/// Paper 000: the sweep of the embedded scenario (M = 1..10, 100 and 300 km/h).
Reproduction reproduce_paper000(const ReproduceSettings& settings);
/// Paper 000's scenario with the station network's IMM against the paper's CA filter.
Reproduction reproduce_paper000_imm(const ReproduceSettings& settings);
/// Paper 001: manoeuvring-target filters and the LSTM networks on 1 000 test paths.
Reproduction reproduce_paper001(const ReproduceSettings& settings);
/// Paper 002: TDOA from a UAV formation; the NCRKF against the nominal, optimal and extended KFs.
Reproduction reproduce_paper002(const ReproduceSettings& settings);
/// Paper 003: the GPS Kalman filter's MSE against time.
Reproduction reproduce_paper003(const ReproduceSettings& settings);

}  // namespace skyfuse::harness
