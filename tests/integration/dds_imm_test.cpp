// The network IMM over loopback DDS (scenarios/paper000-imm.yaml): four station processes
// publish per-mode increments with their likelihood terms, every peer fuses them into the same
// mode probabilities and mixture as the center's stacked IMM, and the run equals its in-process
// twin bit for bit.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

const std::string kScenario = bin("scenarios/paper000-imm.yaml");

std::vector<std::string> imm_run(int domain, const std::filesystem::path& out, int steps,
                                 std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--scenario",   kScenario,
                                   "--stations",   "4",
                                   "--steps",      std::to_string(steps),
                                   "--domain",     std::to_string(domain),
                                   "--out",        out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// modes.csv as (step, source) -> [CV, CA, CT].
std::map<std::pair<int, int>, std::array<double, 3>> read_modes(const std::filesystem::path& csv) {
  std::istringstream in(read_file(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,source,constant_velocity,constant_acceleration,coordinated_turn");
  std::map<std::pair<int, int>, std::array<double, 3>> rows;
  while (std::getline(in, line)) {
    std::array<double, 5> v{};
    std::istringstream fields(line);
    std::string field;
    for (double& x : v) {
      std::getline(fields, field, ',');
      x = std::stod(field);
    }
    rows[{static_cast<int>(v[0]), static_cast<int>(v[1])}] = {v[2], v[3], v[4]};
  }
  return rows;
}

TEST(DdsImm, PeersEqualTheCentralStackedImmAndTheInProcessRunBitForBit) {
  constexpr int kSteps = 2000;  // the whole flight: the turn is 10-18 s
  const auto dir = test_dir();
  const Completed run = run_to_completion(imm_run(181, dir / "out", kSteps), dir / "out.log", 180s);
  ASSERT_TRUE(run.status.exited && run.status.code == 0) << run.output;

  const RunPlan plan = make_run_plan(load_scenario_file(kScenario), {4, kSteps, {}, 0});
  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  ASSERT_EQ(tracks.size(), static_cast<std::size_t>(kSteps * 5));
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);

  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("filter"), "imm");
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);  // mode probabilities included
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-9);
  EXPECT_LT(summary.at("max_abs_diff_mode_probability_central_vs_p2p").get<double>(), 1e-9);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }

  // It is an IMM that switches: CV leads on the straight before the turn, CT in it.
  const auto modes = read_modes(dir / "out" / "modes.csv");
  ASSERT_EQ(modes.size(), static_cast<std::size_t>(kSteps * 5));
  for (const auto& [key, p] : modes) {
    ASSERT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-12) << "step " << key.first;
    if (key.second != 0) {
      ASSERT_EQ(p, modes.at({key.first, 1})) << "peers differ at step " << key.first;
    }
  }
  EXPECT_GT(modes.at({400, 1})[0], 0.5);  // 8 s
  EXPECT_GT(modes.at({750, 1})[2], 0.8);  // 15 s
}

TEST(DdsImm, PeersThatLostDifferentSamplesAgreeAgainAfterTheLossStops) {
  const auto dir = test_dir();
  const Completed run = run_to_completion(
      imm_run(182, dir / "out", 300,
              {"--round-deadline-ms", "50", "--loss", "0.2", "--loss-steps", "100:200"}),
      dir / "out.log", 180s);
  ASSERT_EQ(run.status.code, 0) << run.output;
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_GT(summary.at("max_abs_diff_between_peers").get<double>(), 0.0)
      << "peers that lost different samples cannot agree during the loss";
  EXPECT_EQ(summary.at("peer_spread_end").get<double>(), 0.0);
  int resyncs = 0;
  for (const auto& [station, count] : summary.at("resyncs_by_station").items()) {
    resyncs += count.get<int>();
  }
  EXPECT_GT(resyncs, 0);
  // After the loss every peer holds the same mode probabilities again.
  const auto modes = read_modes(dir / "out" / "modes.csv");
  for (int k = 202; k < 300; ++k) {
    for (int id : {2, 3, 4}) EXPECT_EQ(modes.at({k, id}), modes.at({k, 1})) << k;
  }
}

}  // namespace
}  // namespace skyfuse::test
