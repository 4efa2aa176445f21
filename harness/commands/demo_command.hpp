#pragma once
// `skyfuse demo`: the default scenario through the real system (station processes and the
// center over DDS) at each of its speeds, next to the in-process result, with a plot.

#include <CLI/App.hpp>
#include <string>

namespace skyfuse::harness {

struct DemoOptions {
  std::string out_dir;  ///< empty: results/demo-<date>-<time>
  int domain = 0;
  int stations = 4;
};
void add_demo_command(CLI::App& app, DemoOptions& options);
int run_demo(const DemoOptions& options);

}  // namespace skyfuse::harness
