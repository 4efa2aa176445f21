// What a user sees when something is wrong: bad command lines, a station id the scenario does
// not have, a second station with an id already running, a station that dies, Ctrl-C. Every
// case ends with one clear message, a non-zero exit, no process left and nothing in /dev/shm.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

std::vector<pid_t> processes_on_domain(int domain) {
  return find_processes({"--domain", std::to_string(domain)});
}

// The inode numbers of the sockets a process has open, from /proc/<pid>/fd.
std::set<std::string> socket_inodes(pid_t pid) {
  std::set<std::string> inodes;
  std::error_code error;
  for (const auto& fd : std::filesystem::directory_iterator(
           std::filesystem::path("/proc") / std::to_string(pid) / "fd", error)) {
    const std::string target = std::filesystem::read_symlink(fd.path(), error).string();
    if (target.starts_with("socket:")) inodes.insert(target);
  }
  return inodes;
}

TEST(DdsFaults, RefusesABadCommandLine) {
  const auto dir = test_dir();
  const Completed bogus =
      run_to_completion({bin("skyfuse"), "run", "--bogus"}, dir / "bogus.log", 30s);
  EXPECT_NE(bogus.status.code, 0);
  EXPECT_THAT(bogus.output, HasSubstr("--bogus"));

  const Completed zero =
      run_to_completion({bin("skyfuse"), "run", "--stations", "0"}, dir / "zero.log", 30s);
  EXPECT_NE(zero.status.code, 0);
  EXPECT_THAT(zero.output, HasSubstr("--stations"));

  const Completed too_many = run_to_completion(
      {bin("skyfuse"), "run", "--stations", "11", "--out", (dir / "out").string()},
      dir / "many.log", 30s);
  EXPECT_EQ(too_many.status.code, 2);
  EXPECT_THAT(too_many.output,
              HasSubstr("--stations: must be in [1, 10] for scenario 'paper000', got 11"));
}

TEST(DdsFaults, RefusesAMissingScenario) {
  const auto dir = test_dir();
  const Completed r = run_to_completion(
      {bin("skyfuse"), "run", "--scenario", "/nonexistent/scenario.yaml"}, dir / "r.log", 30s);
  EXPECT_NE(r.status.code, 0);
  EXPECT_THAT(r.output, HasSubstr("/nonexistent/scenario.yaml"));
  EXPECT_THAT(r.output, HasSubstr("does not exist"));
}

TEST(DdsFaults, StationRefusesAnIdNotInTheScenario) {
  const auto dir = test_dir();
  const Completed r = run_to_completion(
      {bin("skyfuse-station"), "--id", "99", "--stations", "3", "--domain", "120"}, dir / "r.log",
      30s);
  EXPECT_TRUE(r.status.exited);
  EXPECT_EQ(r.status.code, 2);
  EXPECT_THAT(r.output, HasSubstr("--id: station 99 is not one of the 3 participating stations "
                                  "of scenario 'paper000' (ids 1, 2, 3)"));
}

TEST(DdsFaults, SecondStationWithARunningIdIsRefusedAndTheRunGoesOn) {
  const auto dir = test_dir();
  const int domain = 121;
  const auto run = start_long_run(domain, 2, dir, {"--run-id", "4242"});

  const Completed twin =
      run_to_completion({bin("skyfuse-station"), "--id", "1", "--stations", "2", "--steps",
                         "1000000", "--run-id", "4242", "--domain", std::to_string(domain)},
                        dir / "twin.log", 60s);
  EXPECT_TRUE(twin.status.exited);
  EXPECT_EQ(twin.status.code, 3) << twin.output;
  EXPECT_THAT(twin.output, HasSubstr("station 1 is already running in run 4242"));

  // The original run was not disturbed.
  EXPECT_FALSE(run->wait(500ms).has_value()) << run->output();
  run->signal(SIGINT);
  const auto status = run->wait(30s);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->code, 130) << run->output();
}

TEST(DdsFaults, HarnessReportsAStationThatDiedInsteadOfHanging) {
  const auto dir = test_dir();
  const int domain = 122;
  const auto shm_before = fastdds_shm_entries();
  const auto run = start_long_run(domain, 3, dir);

  const auto victims = find_processes({"--id", "2", "--domain", std::to_string(domain)});
  ASSERT_EQ(victims.size(), 1U);
  ::kill(victims.front(), SIGKILL);

  const auto status = run->wait(20s);
  ASSERT_TRUE(status.has_value()) << "harness still running after a station died";
  EXPECT_TRUE(status->exited);
  EXPECT_EQ(status->code, 1);
  EXPECT_THAT(run->output(), HasSubstr("station 2 (pid " + std::to_string(victims.front()) +
                                       ") was killed by signal 9"));
  EXPECT_TRUE(eventually([&] { return processes_on_domain(domain).empty(); }, 10s))
      << "processes left behind";
  EXPECT_EQ(fastdds_shm_entries(), shm_before);
}

// A node that inherited the harness's sockets would keep the harness's DDS ports bound, and
// its multicast datagrams queued, after the harness is gone.
TEST(DdsFaults, NodesHoldNoSocketOfTheHarness) {
  const auto dir = test_dir();
  const int domain = 124;
  const auto run = start_long_run(domain, 2, dir);
  const auto harness_sockets = socket_inodes(run->pid());
  ASSERT_FALSE(harness_sockets.empty());
  const auto nodes = processes_on_domain(domain);
  EXPECT_EQ(nodes.size(), 4U);  // harness, center, 2 stations
  for (const pid_t pid : nodes) {
    if (pid == run->pid()) continue;
    const auto node_sockets = socket_inodes(pid);
    EXPECT_FALSE(node_sockets.empty()) << "pid " << pid;
    std::vector<std::string> shared;
    std::set_intersection(harness_sockets.begin(), harness_sockets.end(), node_sockets.begin(),
                          node_sockets.end(), std::back_inserter(shared));
    EXPECT_THAT(shared, ::testing::IsEmpty()) << "pid " << pid;
  }
  run->signal(SIGINT);
  EXPECT_TRUE(run->wait(20s).has_value());
}

// A service manager stops the harness with SIGTERM and reads the status: 128 + 15, as for
// Ctrl-C 128 + 2, and the nodes go with it.
TEST(DdsFaults, SigtermEndsTheRunWithStatus143) {
  const auto dir = test_dir();
  const int domain = 127;
  const auto run = start_long_run(domain, 2, dir);

  run->signal(SIGTERM);
  const auto status = run->wait(20s);
  ASSERT_TRUE(status.has_value());
  EXPECT_TRUE(status->exited);
  EXPECT_EQ(status->code, 143) << run->output();
  EXPECT_THAT(run->output(),
              HasSubstr("run stopped early (interrupted): interrupted by signal 15"));
  // The rounds recorded before the signal are on disk.
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "out" / "summary.json")).at("ended"),
            "interrupted");
  EXPECT_TRUE(eventually([&] { return processes_on_domain(domain).empty(); }, 10s))
      << "processes left behind";
}

TEST(DdsFaults, CtrlCStopsEveryProcessAndLeavesNothingBehind) {
  const auto dir = test_dir();
  const int domain = 123;
  const auto shm_before = fastdds_shm_entries();
  const auto run = start_long_run(domain, 3, dir);
  EXPECT_EQ(processes_on_domain(domain).size(), 5U)  // harness, center, 3 stations
      << run->output();

  run->signal(SIGINT);
  const auto status = run->wait(20s);
  ASSERT_TRUE(status.has_value()) << "harness still running 20 s after SIGINT\n" << run->output();
  EXPECT_EQ(status->code, 130) << run->output();
  EXPECT_THAT(run->output(), HasSubstr("run stopped early (interrupted): interrupted by signal 2"));
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "out" / "summary.json")).at("ended"),
            "interrupted");
  EXPECT_TRUE(eventually([&] { return processes_on_domain(domain).empty(); }, 10s))
      << "processes left behind";
  EXPECT_EQ(fastdds_shm_entries(), shm_before);
}

TEST(DdsFaults, CtrlCDuringABenchKeepsTheRowsMeasuredSoFar) {
  const auto dir = test_dir();
  const int domain = 125;  // the floor's: 126
  const auto out = dir / "out";
  Process bench({bin("skyfuse"), "bench", "--no-micro", "--stations", "1", "4", "--rounds", "20000",
                 "--domain", std::to_string(domain), "--out", out.string()},
                dir / "bench.log");
  // bench.json appears once M = 1 is measured; M = 4 then takes tens of seconds.
  ASSERT_TRUE(eventually([&] { return std::filesystem::exists(out / "bench.json"); }, 90s))
      << bench.output();
  bench.signal(SIGINT);
  const auto status = bench.wait(20s);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->code, 130) << bench.output();

  const auto doc = nlohmann::json::parse(read_file(out / "bench.json"));
  ASSERT_EQ(doc.at("dds").size(), 1U) << doc.dump(2);
  EXPECT_EQ(doc.at("dds")[0].at("stations").get<int>(), 1);
  EXPECT_FALSE(doc.at("dds")[0].contains("error"));
  EXPECT_GT(doc.at("dds")[0].at("rounds_per_s").get<double>(), 0.0);
  EXPECT_TRUE(eventually(
      [&] {
        return processes_on_domain(domain).empty() && processes_on_domain(domain + 1).empty();
      },
      10s))
      << "processes left behind";
}

}  // namespace
}  // namespace skyfuse::test
