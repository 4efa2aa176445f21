// A measurement 50 m off in range, replayed into a real run: with --nis-gate the station that
// made it and the center both refuse it and count it, and the track does not move; without the
// gate it pulls the track tens of metres off.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

std::vector<std::string> run_args(const std::filesystem::path& out,
                                  std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {bin("skyfuse"), "run",      "--stations", "4",     "--steps",
                                   "300",          "--domain", "174",        "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// measurements.csv with station 3's range at step 200 moved by `offset_m`.
std::string with_outlier(const std::string& csv, double offset_m) {
  std::istringstream in(csv);
  std::string out;
  std::string line;
  int changed = 0;
  while (std::getline(in, line)) {
    if (line.starts_with("200,3,")) {
      const auto comma = line.find(',', 6);
      const double range = std::stod(line.substr(6, comma - 6));
      char moved[32];
      std::snprintf(moved, sizeof moved, "%.17g", range + offset_m);
      line = "200,3," + std::string(moved) + line.substr(comma);
      ++changed;
    }
    out += line + '\n';
  }
  EXPECT_EQ(changed, 1);
  return out;
}

// Error of the peer-to-peer track at `step`, from steps.csv.
double p2p_error_at(const std::filesystem::path& steps_csv, int step) {
  return steps_column(steps_csv, "error_p2p_m").at(static_cast<std::size_t>(step));
}

TEST(DdsNisGate, AnOutlierIsRefusedByItsStationAndTheCenterAndCounted) {
  const auto dir = test_dir();
  const Completed clean = run_to_completion(run_args(dir / "clean"), dir / "clean.log", 120s);
  ASSERT_EQ(clean.status.code, 0) << clean.output;
  const auto outlier = dir / "outlier.csv";
  std::ofstream(outlier) << with_outlier(read_file(dir / "clean" / "measurements.csv"), 50.0);

  const Completed gated = run_to_completion(
      run_args(dir / "gated", {"--replay", outlier.string(), "--nis-gate", "0.9999"}),
      dir / "gated.log", 120s);
  ASSERT_EQ(gated.status.code, 0) << gated.output;
  const Completed ungated = run_to_completion(
      run_args(dir / "ungated", {"--replay", outlier.string()}), dir / "ungated.log", 120s);
  ASSERT_EQ(ungated.status.code, 0) << ungated.output;

  const auto summary = nlohmann::json::parse(read_file(dir / "gated" / "summary.json"));
  EXPECT_EQ(summary["dropped_by_kind"]["nis_gate"].get<int>(), 2);
  EXPECT_EQ(summary["dropped_by_node"]["3"]["nis_gate"].get<int>(), 1);
  EXPECT_EQ(summary["dropped_by_node"]["center"]["nis_gate"].get<int>(), 1);
  EXPECT_LT(p2p_error_at(dir / "gated" / "steps.csv", 200), 1.0);
  EXPECT_GT(p2p_error_at(dir / "ungated" / "steps.csv", 200), 10.0);
  EXPECT_LT(summary["rmse_p2p_m"].get<double>(), 0.3);
}

// A gate at probability 0.5 screens out a large share of ordinary measurements. Stations, center
// and the in-process twin apply one round rule, so they screen the same ones, count them the
// same, and hold the same bits.
TEST(DdsNisGate, AGatedRunEqualsItsInProcessTwinBitForBit) {
  constexpr int kStations = 4;
  constexpr int kSteps = 200;
  const auto dir = test_dir();
  const Completed run =
      run_to_completion({bin("skyfuse"), "run", "--stations", std::to_string(kStations), "--steps",
                         std::to_string(kSteps), "--domain", "178", "--nis-gate", "0.5", "--out",
                         (dir / "out").string()},
                        dir / "run.log", 120s);
  ASSERT_EQ(run.status.code, 0) << run.output;

  const RunPlan plan =
      make_run_plan(load_default_scenario(), stations_and_steps(kStations, kSteps));
  RunTrace trace;
  const TwinTracks twin = in_process_twin(plan, NisGate::at_probability(0.5), &trace);
  ASSERT_EQ(twin.size(), static_cast<std::size_t>(kSteps));
  EXPECT_GT(trace.refused_p2p, kSteps * kStations / 10) << "the gate must screen a good share";
  EXPECT_GT(trace.refused_central, kSteps * kStations / 10);
  EXPECT_EQ(difference_from_twin(read_tracks(dir / "out" / "tracks.csv"), plan, twin),
            std::nullopt);
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  int stations_refused = 0;
  for (const StationConfig& s : plan.participants()) {
    stations_refused += summary["dropped_by_node"][std::to_string(s.id)]["nis_gate"].get<int>();
  }
  EXPECT_EQ(stations_refused, trace.refused_p2p);
  EXPECT_EQ(summary["dropped_by_node"]["center"]["nis_gate"].get<int>(), trace.refused_central);
}

}  // namespace
}  // namespace skyfuse::test
