#include "run/bench_scenario.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "report/output_files.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::harness {

BenchScenario load_bench_scenario(const std::string& path, const std::string& default_file,
                                  const std::vector<int>& stations) {
  BenchScenario b;
  b.path = path.empty() ? (executable_dir() / "scenarios" / default_file).string() : path;
  b.scenario = load_scenario_file(b.path);
  for (int m : stations) {
    if (m > static_cast<int>(b.scenario.stations.size())) {
      throw std::invalid_argument(fmt::format("--stations: {} exceeds the {} stations of {}", m,
                                              b.scenario.stations.size(), b.path));
    }
  }
  return b;
}

}  // namespace skyfuse::harness
