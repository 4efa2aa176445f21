#pragma once
// `skyfuse soak`: numerical hygiene over a very long in-process run (default 10^6 steps).

#include <CLI/App.hpp>
#include <cstdint>
#include <string>

namespace skyfuse::harness {

struct SoakOptions {
  std::string scenario_path;  ///< empty: the embedded paper000 scenario
  std::int64_t steps = 1'000'000;
  int stations = 0;  ///< 0: every station of the scenario
};

void add_soak_command(CLI::App& app, SoakOptions& options);
/// 0 when every step was healthy, 1 otherwise.
int run_soak(const SoakOptions& options);

}  // namespace skyfuse::harness
