// The tree exchange over DDS: station processes in clusters, each cluster's aggregator summing
// its members' contributions, the aggregators exchanging their sums, every member fusing the
// round's total its aggregator sends.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

// 16 stations in 4 clusters of 4: every peer holds the same bits, each one the in-process run's
// with the tree's order of summation (not the flat exchange's), central and peer-to-peer within
// 1e-9 m, and nothing refused.
TEST(DdsTree, SixteenStationsInClustersOfFourEqualTheInProcessTreeBitForBit) {
  constexpr int kStations = 16;
  constexpr int kSteps = 200;
  const auto dir = test_dir();
  const std::string scenario = bin("scenarios/ring64.yaml");
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--scenario", scenario, "--stations", std::to_string(kStations),
       "--steps", std::to_string(kSteps), "--exchange", "tree", "--fanout", "4", "--domain", "208",
       "--out", (dir / "out").string()},
      (dir / "out.log").string(), 120s);
  ASSERT_TRUE(run.status.exited && run.status.code == 0) << run.output;

  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  ASSERT_EQ(tracks.size(), static_cast<std::size_t>(kSteps * (kStations + 1)));
  const Scenario loaded = load_scenario_file(scenario);
  RunOverrides overrides;
  overrides.stations = kStations;
  overrides.steps = kSteps;
  const RunPlan flat = make_run_plan(loaded, overrides);
  overrides.exchange = ExchangeConfig::Kind::kTree;
  overrides.fanout = 4;
  const RunPlan plan = make_run_plan(loaded, overrides);
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);
  // The flat exchange sums in another order: its bits are not these, so the run above followed
  // the tree.
  EXPECT_NE(difference_from_twin(tracks, flat, in_process_twin(flat)), std::nullopt);

  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-9);
  EXPECT_EQ(summary.at("rounds_closed_incomplete"), 0);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
}

}  // namespace
}  // namespace skyfuse::test
