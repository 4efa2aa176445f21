#pragma once
// What `skyfuse sweep` reports of a scenario with many aircraft: a table per Monte-Carlo run
// and over all, picture.csv (every step of every run) and picture.json (the summary).

#include <cstdio>
#include <filesystem>
#include <vector>

#include "skyfuse/scenario/scenario.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"

namespace skyfuse::harness {

struct PictureReport {
  const Scenario& scenario;
  const TrafficTruth& truth;
  std::vector<PictureRunResult> runs;
};

void print_picture_table(const PictureReport& report, std::FILE* out);
void write_picture_csv(const PictureReport& report, const std::filesystem::path& path);
void write_picture_json(const PictureReport& report, const std::filesystem::path& path);
/// Whether every run kept the guarantees: peers bit-identical, no association flip.
bool picture_guarantees_held(const PictureReport& report);

}  // namespace skyfuse::harness
