#pragma once
// The scenario a benchmark runs: the one given, or its default beside the executable, with
// every station count asked for checked against it before anything runs (a bad count found
// midway would lose the rows measured so far).

#include <string>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"

namespace skyfuse::harness {

struct BenchScenario {
  std::string path;
  Scenario scenario;
};

/// Loads `path`, or scenarios/`default_file` beside skyfuse when `path` is empty; throws
/// std::invalid_argument naming the first of `stations` that exceeds its stations.
BenchScenario load_bench_scenario(const std::string& path, const std::string& default_file,
                                  const std::vector<int>& stations);

}  // namespace skyfuse::harness
