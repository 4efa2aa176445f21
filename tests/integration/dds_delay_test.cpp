// Delayed and reordered links (`--link-delay-ms`, `--link-jitter-ms`): every increment and
// measurement is held on its link for a seeded time before the receiver sees it. In lock-step a
// round waits for its inputs, so the delay costs time and nothing else: the tracks equal the
// in-process run bit for bit.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

TEST(DdsDelay, LockStepRoundsWaitForDelayedSamplesAndEqualTheInProcessRunBitForBit) {
  const auto dir = test_dir();
  constexpr int kStations = 4;
  constexpr int kSteps = 200;
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--stations", std::to_string(kStations), "--steps",
       std::to_string(kSteps), "--domain", "191", "--link-delay-ms", "10", "--link-jitter-ms", "8",
       "--loss-seed", "3", "--out", (dir / "out").string()},
      dir / "run.log", 120s);
  ASSERT_EQ(run.status.code, 0) << run.output;

  const RunPlan plan = make_run_plan(load_default_scenario(), {kStations, kSteps, {}, 0});
  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  EXPECT_EQ(tracks.size(), static_cast<std::size_t>(kSteps * (kStations + 1)));
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  EXPECT_EQ(summary.at("rounds_closed_incomplete"), 0);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
}

}  // namespace
}  // namespace skyfuse::test
