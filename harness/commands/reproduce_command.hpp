#pragma once
// `skyfuse reproduce PAPER`: a paper's headline results next to this run's, with reproduce.json
// saying which of its claims hold.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace skyfuse::harness {

struct ReproduceOptions {
  std::string paper;
  std::optional<int> runs;
  std::optional<std::uint64_t> seed;
  std::string out_dir;  ///< default: results/reproduce/PAPER
  int threads = 0;
  bool plot = true;
  std::string data_dir;  ///< default: the source tree's data/ (SKYFUSE_DATA_DIR)
};

void add_reproduce_command(CLI::App& app, ReproduceOptions& options);
/// 0 when every claim holds, 1 when one does not.
int run_reproduce(const ReproduceOptions& options);

}  // namespace skyfuse::harness
