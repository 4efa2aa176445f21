// Every way a run of many stations ends — the last round, falling behind real time, a station
// gone silent past --round-timeout, Ctrl-C, a station killed — ends with the documented exit
// status, summary.json and the CSV files of the rounds recorded, and no node killed by a signal
// it was not sent: in particular none by Fast DDS's teardown assertion (signal 6), which
// participants that said goodbye to each other at once used to reach. The last round and falling
// behind are run with 64 stations, each its own process; the three a signal ends with 16 in
// clusters of 4 (the same tree, its discovery a quarter of the participants: each of those
// tests took 110-140 s at 64 on a 2-core machine, most of it discovery).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr int kStations = 64;
constexpr int kSignalledStations = 16;

// The options that make a run ring64's (or `scenario`'s) stations in clusters of 8, each station
// its own process (what these tests stop, kill and count), then `extra`; the number of stations
// is added by whoever starts the run.
std::vector<std::string> ring64_tree(const std::vector<std::string>& extra,
                                     const std::string& scenario = bin("scenarios/ring64.yaml")) {
  std::vector<std::string> options = {
      "--scenario", scenario, "--exchange", "tree", "--stations-per-process", "1"};
  options.insert(options.end(), extra.begin(), extra.end());
  return options;
}

// `skyfuse run` of the 64 stations on `domain` into `dir`/out with `options`, run to its end.
Completed run_until_done(const std::filesystem::path& dir, int domain,
                         const std::vector<std::string>& options) {
  std::vector<std::string> args = {
      bin("skyfuse"),         "run",   "--stations",          std::to_string(kStations), "--domain",
      std::to_string(domain), "--out", (dir / "out").string()};
  args.insert(args.end(), options.begin(), options.end());
  return run_to_completion(args, dir / "run.log", 240s);
}

// A long run of ring64's first kSignalledStations stations (the fixture's start_long_run), once
// its rounds have begun; discovery of many processes may take far longer than the fixture's
// default wait.
std::unique_ptr<Process> start_long_run_to_signal(int domain, const std::filesystem::path& dir,
                                                  const std::vector<std::string>& extra = {}) {
  return start_long_run(domain, kSignalledStations, dir, ring64_tree(extra), 150s);
}

// The process of station `id` on `domain`; a failure unless there is exactly one.
pid_t station_pid(int id, int domain) {
  const auto pids =
      find_processes({"--id", std::to_string(id), "--domain", std::to_string(domain)});
  EXPECT_EQ(pids.size(), 1U);
  return pids.empty() ? -1 : pids.front();
}

// What every run leaves, however it ended: summary.json saying how, steps.csv with a row per
// step recorded, and every one of the `stations` + 1 nodes accounted for, none killed by a
// signal except `killed` (node name -> the signal the test or the harness sent it).
nlohmann::json expect_files_and_clean_exits(const std::filesystem::path& out,
                                            const std::string& output, const std::string& ended,
                                            int stations,
                                            const std::map<std::string, int>& killed = {}) {
  EXPECT_THAT(output, Not(HasSubstr("Assertion"))) << output;
  if (!std::filesystem::exists(out / "summary.json")) {
    ADD_FAILURE() << "no summary.json\n" << output;
    return {};
  }
  auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("ended"), ended) << output;
  EXPECT_GE(summary.at("steps_planned").get<int>(), summary.at("steps").get<int>());
  // steps.csv: a header and a row per recorded step.
  const std::string steps_csv = read_file(out / "steps.csv");
  EXPECT_EQ(std::count(steps_csv.begin(), steps_csv.end(), '\n'),
            summary.at("steps").get<int>() + 1);
  EXPECT_TRUE(std::filesystem::exists(out / "tracks.csv"));
  const auto& exits = summary.at("node_exits");
  EXPECT_EQ(exits.size(), static_cast<std::size_t>(stations + 1)) << exits.dump();
  for (const auto& [node, how] : exits.items()) {
    const auto sent = killed.find(node);
    if (sent != killed.end()) {
      EXPECT_THAT(how.get<std::string>(), HasSubstr("signal " + std::to_string(sent->second)))
          << node;
    } else {
      EXPECT_EQ(how, "exit 0") << node << " (" << how << ")\n" << output;
    }
  }
  return summary;
}

TEST(DdsRunEnd, SixtyFourStationsLeaveCleanlyAfterTheLastRound) {
  const auto dir = test_dir();
  const Completed run = run_until_done(dir, 135, ring64_tree({"--steps", "40"}));
  EXPECT_TRUE(run.status.exited && run.status.code == 0) << run.output;
  const auto summary = expect_files_and_clean_exits(dir / "out", run.output, "complete", kStations);
  EXPECT_EQ(summary.value("steps", 0), 40);
}

// 64 stations at 2 kHz with a 0.25 ms deadline: no 2-core host carries that, so the run falls
// behind at once and stops after --round-timeout; its files say how far it got and why.
TEST(DdsRunEnd, ARealTimeRunThatFallsBehindStopsWithItsFiles) {
  const auto dir = test_dir();
  std::string scenario = read_file(bin("scenarios/ring64.yaml"));
  scenario = std::regex_replace(scenario, std::regex("time_step_s: 0\\.02"), "time_step_s: 0.0005");
  ASSERT_THAT(scenario, HasSubstr("time_step_s: 0.0005"));
  const auto fast = dir / "ring64_2khz.yaml";
  std::ofstream(fast) << scenario;
  const Completed run =
      run_until_done(dir, 136,
                     ring64_tree({"--steps", "2000", "--realtime-deadline-ms", "0.25",
                                  "--round-timeout", "2", "--best-effort"},
                                 fast.string()));
  EXPECT_TRUE(run.status.exited) << run.output;
  EXPECT_EQ(run.status.code, 3) << run.output;
  EXPECT_THAT(run.output, HasSubstr("run stopped early (fell_behind): real-time run fell behind"));
  EXPECT_THAT(run.output, HasSubstr("could not carry 64 stations at 2000 Hz"));
  const auto summary =
      expect_files_and_clean_exits(dir / "out", run.output, "fell_behind", kStations);
  ASSERT_TRUE(summary.contains("realtime")) << summary.dump();
  const auto& realtime = summary.at("realtime");
  EXPECT_LT(summary.at("steps").get<int>(), 2000);
  EXPECT_LT(realtime.at("rounds_all_inputs_in_time").get<double>(), 1.0);
  EXPECT_GT(realtime.at("behind_s").get<double>(), 2.0);
  EXPECT_GT(realtime.at("steps_scheduled").get<int>(), summary.at("steps").get<int>());
  EXPECT_FALSE(realtime.at("track_age_ms_histogram").empty());
  EXPECT_GT(summary.at("kernel").at("cpu_ms_per_station_round").get<double>(), 0.0);
  EXPECT_THAT(summary.at("host_verdict").get<std::string>(),
              HasSubstr("could not carry 64 stations at 2000 Hz with a 0.25 ms deadline"));
}

// A station that stops (SIGSTOP) delivers nothing: after --round-timeout the run stops with
// what it recorded; the harness kills the stopped process (SIGKILL: SIGTERM waits while it is
// stopped) and every other node leaves by itself.
TEST(DdsRunEnd, ASilentStationStopsALockStepRunAtTheRoundTimeout) {
  const auto dir = test_dir();
  const auto run = start_long_run_to_signal(137, dir, {"--round-timeout", "3"});
  ASSERT_FALSE(HasFailure());
  const pid_t victim = station_pid(9, 137);
  ASSERT_FALSE(HasFailure());
  ::kill(victim, SIGSTOP);
  const auto status = run->wait(120s);
  ASSERT_TRUE(status.has_value()) << run->output();
  EXPECT_TRUE(status->exited);
  EXPECT_EQ(status->code, 3) << run->output();
  EXPECT_THAT(run->output(), HasSubstr("run stopped early (round_timeout): station 9 is running "
                                       "but sent no track for 3.0 s"));
  const auto summary = expect_files_and_clean_exits(dir / "out", run->output(), "round_timeout",
                                                    kSignalledStations, {{"station 9", SIGKILL}});
  EXPECT_GT(summary.value("steps", 0), 0);
}

TEST(DdsRunEnd, CtrlCStopsTheRunWithItsFiles) {
  const auto dir = test_dir();
  const auto run = start_long_run_to_signal(138, dir);
  ASSERT_FALSE(HasFailure());
  run->signal(SIGINT);
  const auto status = run->wait(60s);
  ASSERT_TRUE(status.has_value()) << run->output();
  EXPECT_TRUE(status->exited);
  EXPECT_EQ(status->code, 130) << run->output();
  EXPECT_THAT(run->output(), HasSubstr("run stopped early (interrupted): interrupted by signal 2"));
  const auto summary =
      expect_files_and_clean_exits(dir / "out", run->output(), "interrupted", kSignalledStations);
  EXPECT_GT(summary.value("steps", 0), 0);
}

TEST(DdsRunEnd, AKilledStationStopsTheRunWithItsFiles) {
  const auto dir = test_dir();
  const auto shared_memory_before = fastdds_shm_entries();  // UDP only: none may appear
  const auto run = start_long_run_to_signal(139, dir);
  ASSERT_FALSE(HasFailure());
  const pid_t victim = station_pid(13, 139);
  ASSERT_FALSE(HasFailure());
  ::kill(victim, SIGKILL);
  const auto status = run->wait(60s);
  ASSERT_TRUE(status.has_value()) << run->output();
  EXPECT_TRUE(status->exited);
  EXPECT_EQ(status->code, 1) << run->output();
  EXPECT_THAT(run->output(), HasSubstr("run stopped early (node_failed): station 13 (pid " +
                                       std::to_string(victim) + ") was killed by signal 9"));
  const auto summary = expect_files_and_clean_exits(dir / "out", run->output(), "node_failed",
                                                    kSignalledStations, {{"station 13", SIGKILL}});
  EXPECT_GT(summary.value("steps", 0), 0);
  EXPECT_EQ(fastdds_shm_entries(), shared_memory_before);
}

}  // namespace
}  // namespace skyfuse::test
