// The scans a recording draws (sim/picture_detections.hpp) are the stations' own: as many
// detections and false alarms as the in-process run fused, and each aircraft's detection where
// that aircraft is, within its radar's noise.
#include "skyfuse/sim/picture_detections.hpp"

#include <gtest/gtest.h>

#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/picture_run.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"

namespace skyfuse {
namespace {

TEST(PictureDetections, AreTheScansTheStationsFused) {
  Scenario scenario =
      load_scenario_file(std::string(SKYFUSE_SOURCE_DIR) + "/scenarios/uam-city.yaml");
  scenario.steps = 40;
  constexpr int kStations = 4;
  constexpr std::uint64_t kRun = 3;
  const TrafficTruth truth = build_traffic_truth(scenario);
  const PictureRunResult run = run_picture(scenario, truth.targets, kStations, kRun);

  std::uint64_t detections = 0;
  std::uint64_t false_alarms = 0;
  double farthest_m = 0.0;
  for (int k = 0; k < scenario.steps; ++k) {
    const auto scans = scan_positions_at(scenario, truth.targets, kStations, kRun, k);
    ASSERT_EQ(scans.size(), static_cast<std::size_t>(kStations));
    for (std::size_t s = 0; s < scans.size(); ++s) {
      EXPECT_EQ(scans[s].station_id, scenario.stations[s].id);
      ASSERT_EQ(scans[s].positions.size(), scans[s].target.size());
      detections += scans[s].positions.size();
      for (std::size_t d = 0; d < scans[s].positions.size(); ++d) {
        const int target = scans[s].target[d];
        if (target < 0) {
          ++false_alarms;
          continue;
        }
        const Vector3 truth_at = truth.targets[static_cast<std::size_t>(target)].at(k).head<3>();
        farthest_m = std::max(farthest_m, (scans[s].positions[d] - truth_at).norm());
      }
    }
  }
  EXPECT_EQ(detections, run.detections);
  EXPECT_EQ(false_alarms, run.false_alarms);
  EXPECT_GT(detections, false_alarms);
  // uam-city's radars: 5 m in range, 2.6 mrad in angle (31 m at their 12 km reach): within 8
  // of those sigmas.
  EXPECT_LT(farthest_m, 250.0);
}

}  // namespace
}  // namespace skyfuse
