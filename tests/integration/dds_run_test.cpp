// The system over loopback DDS: station processes and the fusion center, driven by the harness.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <atomic>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/run_plan.hpp"

namespace skyfuse::test {
namespace {

// The latency_us column of rounds.csv (header step,latency_us), in file order.
std::vector<double> read_round_latencies(const std::filesystem::path& csv) {
  std::istringstream in(read_file(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,latency_us");
  std::vector<double> latencies;
  while (std::getline(in, line)) latencies.push_back(std::stod(line.substr(line.find(',') + 1)));
  return latencies;
}

using namespace std::chrono_literals;
constexpr int kSteps = 200;

Completed skyfuse_run(int stations, int domain, const std::filesystem::path& out,
                      std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--stations",   std::to_string(stations),
                                   "--steps",      std::to_string(kSteps),
                                   "--domain",     std::to_string(domain),
                                   "--out",        out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return run_to_completion(args, out.string() + ".log", 120s);
}

class DdsRun : public ::testing::TestWithParam<int> {};

TEST_P(DdsRun, EveryPeerAgreesAndTheRunEqualsTheInProcessOneBitForBit) {
  const int m = GetParam();
  const auto dir = test_dir();
  const Completed run = skyfuse_run(m, 100 + m, dir / "out");
  ASSERT_TRUE(run.status.exited && run.status.code == 0) << run.output;

  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  ASSERT_EQ(tracks.size(), static_cast<std::size_t>(kSteps * (m + 1)));

  // The same run in-process: the same core code on the same seed.
  const RunPlan plan = make_run_plan(load_default_scenario(), stations_and_steps(m, kSteps));
  const TwinTracks twin = in_process_twin(plan);
  ASSERT_EQ(twin.size(), static_cast<std::size_t>(kSteps));
  EXPECT_EQ(difference_from_twin(tracks, plan, twin), std::nullopt);
  for (int k = 0; k < kSteps; ++k) {
    const StateRow& central = tracks.at({k, 0});
    const StateRow& first_peer = tracks.at({k, plan.participants().front().id});
    double distance_sq = 0.0;
    for (int i = 0; i < 3; ++i)
      distance_sq += (central[i] - first_peer[i]) * (central[i] - first_peer[i]);
    ASSERT_LT(std::sqrt(distance_sq), 1e-6) << "step " << k;
  }
  // tracks.csv carries each track's covariance: the peers' the same bits, a positive definite
  // matrix, close to the center's.
  const TrackRows covariances = read_track_covariances(dir / "out" / "tracks.csv");
  const int n = 9;
  ASSERT_EQ(covariances.at({0, 0}).size(), static_cast<std::size_t>(n * (n + 1) / 2));
  for (int k = 0; k < kSteps; ++k) {
    const StateRow& first = covariances.at({k, plan.participants().front().id});
    for (const StationConfig& s : plan.participants()) {
      ASSERT_EQ(covariances.at({k, s.id}), first) << "step " << k << " station " << s.id;
    }
    Eigen::MatrixXd p(n, n);
    for (int i = 0, at = 0; i < n; ++i) {
      for (int j = i; j < n; ++j, ++at) p(i, j) = p(j, i) = first[static_cast<std::size_t>(at)];
    }
    ASSERT_EQ(p.llt().info(), Eigen::Success) << "step " << k;
    const StateRow& central = covariances.at({k, 0});
    for (std::size_t i = 0; i < central.size(); ++i) {
      ASSERT_NEAR(central[i], first[i], 1e-9) << "step " << k << " entry " << i;
    }
  }

  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("stations"), m);
  EXPECT_EQ(summary.at("steps"), kSteps);
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  EXPECT_FALSE(summary.contains("realtime")) << "a lock-step run has no real-time figures";
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-6);
  EXPECT_GT(summary.at("rounds_per_s").get<double>(), 0.0);
  // Every round was timed, and the summary's latencies are those of rounds.csv.
  std::vector<double> latencies = read_round_latencies(dir / "out" / "rounds.csv");
  ASSERT_EQ(latencies.size(), static_cast<std::size_t>(kSteps));
  std::sort(latencies.begin(), latencies.end());
  EXPECT_GT(latencies.front(), 0.0);
  const double median = latencies[(latencies.size() + 1) / 2 - 1];  // nearest rank
  EXPECT_NEAR(summary.at("round_latency_us_p50").get<double>(), median, 0.051);
  EXPECT_NEAR(summary.at("round_latency_us_max").get<double>(), latencies.back(), 0.051);
  EXPECT_GT(summary.at("rmse_p2p_m").get<double>(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Stations, DdsRun, ::testing::Values(1, 3, 8), [](const auto& param_info) {
  std::string name = "M";  // not "M" + ...: GCC 12 -Wrestrict false positive
  name += std::to_string(param_info.param);
  return name;
});

// `skyfuse run` of a scenario file with `stations` participants: every peer holds the same bits,
// central equals peer-to-peer within 1e-6 m, nothing is refused, and every track equals the
// in-process run's bit for bit. Returns the run's folder.
std::filesystem::path expect_run_equals_twin(const std::string& scenario_file, int stations,
                                             int domain) {
  const auto dir = test_dir();
  const std::string scenario = bin("scenarios/" + scenario_file);
  const Completed run = skyfuse_run(stations, domain, dir / "out", {"--scenario", scenario});
  EXPECT_TRUE(run.status.exited && run.status.code == 0) << run.output;

  const RunPlan plan =
      make_run_plan(load_scenario_file(scenario), stations_and_steps(stations, kSteps));
  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  EXPECT_EQ(tracks.size(), static_cast<std::size_t>(kSteps * (stations + 1)));
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-6);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
  return dir / "out";
}

// A constant-velocity model over DDS: the stations and the center run its 6-entry state as they
// run the 9-entry one, and every track they publish has its six entries.
TEST(DdsRunModels, AConstantVelocityRunEqualsTheInProcessRunBitForBit) {
  const auto out = expect_run_equals_twin("paper000-cv.yaml", 4, 203);
  const std::string tracks = read_file(out / "tracks.csv");
  EXPECT_EQ(tracks.substr(0, tracks.find('\n')),
            "step,source,x0,x1,x2,x3,x4,x5,p0_0,p0_1,p0_2,p0_3,p0_4,p0_5,p1_1,p1_2,p1_3,p1_4,"
            "p1_5,p2_2,p2_3,p2_4,p2_5,p3_3,p3_4,p3_5,p4_4,p4_5,p5_5,settled");
}

// The unscented information filter over DDS: each station's statistically linearised increment,
// summed by every peer, and the center's sum of the same increments computed from the raw
// measurements: within 1e-9 m of each other, and bit for bit the in-process run's.
TEST(DdsRunModels, AnUnscentedFilterRunEqualsTheInProcessRunBitForBit) {
  const auto out = expect_run_equals_twin("paper000-ukf.yaml", 4, 204);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-9);
  EXPECT_LT(summary.at("rmse_p2p_m").get<double>(), 1.0);
}

// Paper 000's radars with the aircraft's own GPS report as a fifth participant: station
// processes of two sensor kinds, the center stacking both.
TEST(DdsRunMixed, RadarsAndTheAircraftsGpsEqualTheInProcessRunBitForBit) {
  const auto out = expect_run_equals_twin("paper000-gps.yaml", 5, 179);
  // The GPS's rows name their sensor in measurements.csv.
  EXPECT_NE(read_file(out / "measurements.csv").find(",11,position_velocity,"), std::string::npos);
}

// Paper 002's formation: three TDOA receivers as station processes (a one-component sensor
// whose site is fixed in the reference UAV's frame), each publishing its bias-compensated NCRKF
// increment; the center computes the same increments from the raw measurements and fuses them
// onto its own prior, so central and peer-to-peer hold the same bits.
TEST(DdsRunTdoa, ThreeNcrkfReceiversOfPaper002EqualTheCenterAndTheInProcessRunBitForBit) {
  const auto out = expect_run_equals_twin("paper002.yaml", 3, 183);
  EXPECT_NE(read_file(out / "measurements.csv").find("step,station_id,range_difference_m"),
            std::string::npos);
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 0.0);
}

// The same receivers with the EKF on the range differences.
TEST(DdsRunTdoa, ThreeEkfReceiversOfPaper002EqualTheInProcessRunBitForBit) {
  expect_run_equals_twin("paper002-ekf.yaml", 3, 184);
}

TEST(DdsRunDeterminism, SameSeedGivesTheSameBytesEvenWithTheOtherCoreBusy) {
  const auto dir = test_dir();
  const Completed quiet = skyfuse_run(3, 110, dir / "quiet");
  ASSERT_EQ(quiet.status.code, 0) << quiet.output;

  std::atomic<bool> done{false};
  std::thread busy([&] {
    volatile double sink = 0.0;
    while (!done) sink = sink + 1.0;
  });
  const Completed loaded = skyfuse_run(3, 111, dir / "loaded");
  done = true;
  busy.join();
  ASSERT_EQ(loaded.status.code, 0) << loaded.output;

  for (const char* file : {"steps.csv", "tracks.csv", "measurements.csv"}) {
    const std::string a = read_file(dir / "quiet" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, read_file(dir / "loaded" / file)) << file << " differs between the two runs";
  }
}

TEST(DdsRunReplay, ReplayingRecordedMeasurementsReproducesTheRun) {
  const auto dir = test_dir();
  const Completed recorded = skyfuse_run(3, 112, dir / "recorded");
  ASSERT_EQ(recorded.status.code, 0) << recorded.output;
  const Completed replayed = skyfuse_run(
      3, 112, dir / "replayed", {"--replay", (dir / "recorded" / "measurements.csv").string()});
  ASSERT_EQ(replayed.status.code, 0) << replayed.output;
  EXPECT_EQ(read_file(dir / "recorded" / "tracks.csv"), read_file(dir / "replayed" / "tracks.csv"));

  // And a different seed gives different tracks, so the equality above is not vacuous.
  const Completed other = skyfuse_run(3, 112, dir / "other", {"--mc-run", "1"});
  ASSERT_EQ(other.status.code, 0) << other.output;
  EXPECT_NE(read_file(dir / "recorded" / "tracks.csv"), read_file(dir / "other" / "tracks.csv"));
}

}  // namespace
}  // namespace skyfuse::test

namespace skyfuse::test {
namespace {

TEST(DdsBench, MeasuresEachStationCountAgainstItsFloorIntoBenchJson) {
  // Behaviour only: every requested M gets a row with the run and its floors measured, its
  // ratios are those of its rates, and the machine is named. What the numbers are is the bench's
  // job.
  const auto dir = test_dir();
  const Completed bench =
      run_to_completion({bin("skyfuse"), "bench", "--no-micro", "--stations", "1", "2", "--rounds",
                         "30", "--domain", "190",  // its floors: 191
                         "--out", (dir / "out").string()},
                        dir / "bench.log", std::chrono::seconds(180));
  ASSERT_EQ(bench.status.code, 0) << bench.output;
  const auto doc = nlohmann::json::parse(read_file(dir / "out" / "bench.json"));
  EXPECT_GE(doc.at("machine").at("cores").get<int>(), 1);
  EXPECT_FALSE(doc.at("machine").at("cpu_model").get<std::string>().empty());
  EXPECT_FALSE(doc.contains("micro_ns"));
  const auto& rows = doc.at("dds");
  ASSERT_EQ(rows.size(), 2U) << doc.dump(2);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    SCOPED_TRACE(row.dump());
    ASSERT_FALSE(row.contains("error"));
    EXPECT_EQ(row.at("stations").get<int>(), static_cast<int>(i) + 1);
    EXPECT_EQ(row.at("rounds").get<int>(), 30);
    EXPECT_GT(row.at("rounds_per_s").get<double>(), 0.0);
    EXPECT_GT(row.at("floor_rounds_per_s").get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(
        row.at("ratio_to_floor").get<double>(),
        row.at("rounds_per_s").get<double>() / row.at("floor_rounds_per_s").get<double>());
    // At M = 2 each round of this floor needs every echo to hear the other's sample.
    EXPECT_GT(row.at("all_to_all_floor_rounds_per_s").get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(row.at("ratio_to_all_to_all_floor").get<double>(),
                     row.at("rounds_per_s").get<double>() /
                         row.at("all_to_all_floor_rounds_per_s").get<double>());
    EXPECT_GT(row.at("all_to_all_floor_latency_us_p50").get<double>(), 0.0);
    EXPECT_GT(row.at("round_latency_us_p50").get<double>(), 0.0);
    EXPECT_GT(row.at("discovery_s").get<double>(), 0.0);
    EXPECT_GT(row.at("floor_discovery_s").get<double>(), 0.0);
  }
  // The run behind each row is kept, all its rounds recorded.
  EXPECT_EQ(read_tracks(dir / "out" / "run-M2" / "tracks.csv").size(), 30U * 3U);
}

TEST(DdsRunRealtime, NodesStepOnTheWallClockAndTheHarnessReportsDeadlinesAndAges) {
  // Behaviour only (speed is for the benchmarks): every step is recorded, every track names
  // the stations it fused, and the summary carries the real-time figures.
  const auto dir = test_dir();
  const Completed run =
      run_to_completion({bin("skyfuse"), "run", "--stations", "3", "--steps", "100", "--domain",
                         "113", "--realtime-deadline-ms", "15", "--out", (dir / "out").string()},
                        dir / "run.log", std::chrono::seconds(120));
  ASSERT_EQ(run.status.code, 0) << run.output;
  EXPECT_EQ(read_tracks(dir / "out" / "tracks.csv").size(), 100U * 4U);
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  ASSERT_TRUE(summary.contains("realtime")) << summary.dump(2);
  const auto& rt = summary.at("realtime");
  EXPECT_EQ(rt.at("deadline_ms"), 15.0);
  // 3 stations at 50 Hz are far from what this machine can do: most rounds in time.
  EXPECT_GT(rt.at("rounds_all_inputs_in_time").get<double>(), 0.5);
  // A track is at least as old as the work of its round, and younger than the step.
  EXPECT_GT(rt.at("track_age_ms_p50").get<double>(), 0.0);
  EXPECT_LT(rt.at("track_age_ms_p50").get<double>(), 20.0);
  // Fusing what arrived by the deadline still tracks (3 stations: well under a metre).
  EXPECT_LT(summary.at("rmse_p2p_m").get<double>(), 1.0);
}

}  // namespace
}  // namespace skyfuse::test
