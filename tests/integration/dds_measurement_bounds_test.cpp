// A station 1.5 m under the aircraft's path with a range noise of 5 m: some of its simulated
// ranges come out at or below zero, which no sensor reports and every receiver refuses. The
// station that made such a measurement refuses it too, so the peers and the center fuse the
// same data: the two tracks stay equal, and the station, the center and the harness's recorder
// count the same refusals.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

constexpr const char* kClosePass = R"(name: close_pass
seed: 5
time_step_s: 0.02
steps: 100
target:
  initial_position_m: [-1200.0, -300.0, 450.0]
  heading_deg: 10.0
  climb_deg: 0.0
  speeds_kmh: [100]
stations:
  - {id: 1, position_m: [-400.0, 1200.0, 40.0], noise_std: [0.1, 0.01, 0.01]}
  - {id: 2, position_m: [-1200.0, -300.0, 448.5], noise_std: [5.0, 0.01, 0.01]}
measurement_noise:
  scale: none
filter:
  process_noise_std: {position_m: 0.5, velocity_mps: 0.1, acceleration_mps2: 0.05}
  initial_covariance_diag: 1.0
  initial_state_error: sampled
)";

TEST(DdsMeasurementBounds, AStationRefusesItsOwnImpossibleRangeAsTheCenterDoes) {
  const auto dir = test_dir();
  const auto scenario = dir / "close_pass.yaml";
  std::ofstream(scenario) << kClosePass;
  // A refused measurement never reaches the recorder, which closes that round at its deadline:
  // a short one keeps the test short.
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--scenario", scenario.string(), "--stations", "2", "--domain", "176",
       "--round-deadline-ms", "100", "--out", (dir / "out").string()},
      dir / "run.log", 120s);
  ASSERT_EQ(run.status.code, 0) << run.output;

  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  const auto& by_node = summary["dropped_by_node"];
  const int by_station = by_node["2"].value("out_of_range", 0);
  EXPECT_GT(by_station, 0) << "the scenario should produce impossible ranges: " << by_node;
  EXPECT_EQ(by_node["center"].value("out_of_range", 0), by_station) << by_node;
  EXPECT_EQ(by_node["harness"].value("out_of_range", 0), by_station) << by_node;
  EXPECT_LT(summary["max_abs_diff_central_vs_p2p"].get<double>(), 1e-6);
  EXPECT_EQ(summary["max_abs_diff_between_peers"].get<double>(), 0.0);
}

}  // namespace
}  // namespace skyfuse::test
