// Beyond one loopback interface: `skyfuse run --hosts N` places the processes on N network
// namespaces joined by a bridge, with multicast off on every host's interface, so the nodes can
// find each other only through the harness's discovery server; and `--discovery-server` on one
// host. Either way the tracks equal the in-process run bit for bit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>

#include "integration/run_fixture.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr int kSteps = 200;

// What a shell command prints on stdout.
std::string output_of(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  pclose(pipe);
  return out;
}

// Why this process cannot make simulated hosts, if it cannot.
std::optional<std::string> why_no_hosts() {
  if (geteuid() != 0) return "--hosts creates network namespaces: root only";
  if (std::system("ip -V > /dev/null 2>&1") != 0) return "no `ip` (iproute2)";
  return std::nullopt;
}

// Nothing of the run whose output is `output` is left behind: no namespace, no bridge. Only
// this run's are looked for, as another test's run may be up meanwhile.
void expect_hosts_removed(const std::string& output) {
  std::smatch bridge;
  EXPECT_TRUE(std::regex_search(output, bridge, std::regex("on bridge sfbr([0-9]+)"))) << output;
  if (!bridge.empty()) {
    const std::string tag = bridge[1];
    EXPECT_THAT(output_of("ip netns list"), Not(HasSubstr("skyfuse-" + tag + "-h")));
    EXPECT_THAT(output_of("ip -o link show type bridge"), Not(HasSubstr("sfbr" + tag + ":")));
  }
}

// Runs `skyfuse run` with `extra` and checks every track against the in-process twin; returns
// summary.json.
nlohmann::json expect_equal_to_twin(int stations, int domain,
                                    const std::vector<std::string>& extra) {
  const auto dir = test_dir();
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--stations",   std::to_string(stations),
                                   "--steps",      std::to_string(kSteps),
                                   "--domain",     std::to_string(domain),
                                   "--out",        (dir / "out").string(),
                                   "--verbose"};
  args.insert(args.end(), extra.begin(), extra.end());
  const Completed run = run_to_completion(args, dir / "run.log", 120s);
  EXPECT_EQ(run.status.code, 0) << run.output;
  if (run.status.code != 0) return {};

  if (std::find(extra.begin(), extra.end(), "--hosts") != extra.end()) {
    expect_hosts_removed(run.output);
  }
  return expect_default_run_equals_twin(dir / "out", stations, kSteps);
}

TEST(DdsHosts, FourStationsOnThreeHostsEqualTheInProcessRunBitForBit) {
  if (const auto why = why_no_hosts()) GTEST_SKIP() << *why;
  const auto summary = expect_equal_to_twin(4, 188, {"--hosts", "3"});
  EXPECT_EQ(summary["network"]["hosts"], 3);
  EXPECT_THAT(summary["network"]["discovery"].get<std::string>(), HasSubstr("server 198.18."));
}

// Multicast discovery across the hosts' bridge, no server: the run says so and equals its twin.
TEST(DdsHosts, FourStationsOnThreeHostsDiscoveringByMulticastEqualTheInProcessRun) {
  if (const auto why = why_no_hosts()) GTEST_SKIP() << *why;
  const auto summary = expect_equal_to_twin(4, 186, {"--hosts", "3", "--discovery", "multicast"});
  EXPECT_EQ(summary["network"]["hosts"], 3);
  EXPECT_EQ(summary["network"]["discovery"], "multicast");
}

// Peer discovery across hosts: each process listed by its host's address and participant id,
// and announcing itself to those it exchanges with (here, as the flat exchange has it, all).
TEST(DdsHosts, FourStationsOnThreeHostsDiscoveringTheirPeersEqualTheInProcessRun) {
  if (const auto why = why_no_hosts()) GTEST_SKIP() << *why;
  const auto summary = expect_equal_to_twin(4, 223, {"--hosts", "3", "--discovery", "peers"});
  EXPECT_EQ(summary["network"]["hosts"], 3);
  EXPECT_EQ(summary["network"]["discovery"], "peers");
  const auto& known_by_node = summary["network"]["participants_known_by_node"];
  EXPECT_EQ(known_by_node.size(), 5u);  // the center and four stations reported
  for (const auto& [node, known] : known_by_node.items()) {
    EXPECT_EQ(known.get<int>(), 5) << node;  // the harness, the center and the other stations
  }
}

// Two stations to a process across two hosts (the center and stations 1-2 on the first, stations
// 3-4 on the second): the flat exchange's samples between the two processes cross the bridge,
// those within one pass in memory, and the tracks are the in-process run's. Each station's
// participant knows the harness, the center and the other process.
TEST(DdsHosts, StationsSharingProcessesOnTwoHostsEqualTheInProcessRun) {
  if (const auto why = why_no_hosts()) GTEST_SKIP() << *why;
  const auto summary = expect_equal_to_twin(
      4, 66, {"--hosts", "2", "--discovery", "peers", "--stations-per-process", "2"});
  EXPECT_EQ(summary["network"]["hosts"], 2);
  EXPECT_EQ(summary["network"]["stations_per_process"], 2);
  const auto& known_by_node = summary["network"]["participants_known_by_node"];
  EXPECT_EQ(known_by_node.size(), 5u);
  for (const auto& [node, known] : known_by_node.items()) {
    EXPECT_EQ(known.get<int>(), 3) << node;
  }
}

// Many aircraft on three hosts: every station's picture the in-process run's in every round,
// the center's too (the harness checks each round against its twin and says so in the summary).
TEST(DdsHosts, ManyAircraftOnThreeHostsHoldTheInProcessPictureInEveryRound) {
  if (const auto why = why_no_hosts()) GTEST_SKIP() << *why;
  const auto dir = test_dir();
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--scenario", bin("scenarios/uam-city.yaml"), "--stations", "4",
       "--steps", "60", "--hosts", "3", "--domain", "220", "--out", (dir / "out").string()},
      dir / "run.log", 120s);
  ASSERT_EQ(run.status.code, 0) << run.output;
  expect_hosts_removed(run.output);
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_TRUE(summary.at("peers_identical").get<bool>());
  EXPECT_TRUE(summary.at("equals_in_process").get<bool>());
  EXPECT_TRUE(summary.at("center_equals_in_process").get<bool>());
  EXPECT_EQ(summary.at("steps").get<int>(), 60);
  // The datagrams of every host were counted, not only the harness's.
  EXPECT_GT(summary.at("datagrams_received_per_round").get<double>(), 0.0);
}

// The harness serves discovery only to the hosts it makes; peer lists are its to write.
TEST(DdsHosts, ServerDiscoveryIsRefusedWithoutHostsAndPeerDiscoveryWithoutTheHarnessStarting) {
  const auto dir = test_dir();
  const Completed server = run_to_completion(
      {bin("skyfuse"), "run", "--discovery", "server", "--out", (dir / "out").string()},
      dir / "server.log", 30s);
  EXPECT_NE(server.status.code, 0);
  EXPECT_THAT(server.output, HasSubstr("--discovery server: the harness serves discovery for "
                                       "--hosts only"));
  const Completed external = run_to_completion({bin("skyfuse"), "run", "--discovery", "peers",
                                                "--external", "--out", (dir / "out").string()},
                                               dir / "external.log", 30s);
  EXPECT_NE(external.status.code, 0);
  EXPECT_THAT(external.output, HasSubstr("--discovery peers: not with --external"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(DdsHosts, RefusedWithoutRootBeforeWritingAnything) {
  const auto dir = test_dir();
  std::vector<std::string> args = {bin("skyfuse"), "run", "--hosts", "2",
                                   "--steps",      "5",   "--out",   (dir / "out").string()};
  if (geteuid() == 0) {  // as nobody: what a user without root sees
    if (std::system("setpriv --help > /dev/null 2>&1") != 0) GTEST_SKIP() << "no setpriv";
    std::filesystem::permissions(dir, std::filesystem::perms::all);
    args.insert(args.begin(),
                {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"});
  }
  const Completed run = run_to_completion(args, dir / "run.log", 60s);
  EXPECT_NE(run.status.code, 0);
  EXPECT_THAT(run.output, HasSubstr("--hosts: creating network namespaces needs root"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(DdsDiscoveryServer, NodesFindEachOtherThroughTheHarnessOnLoopback) {
  const auto summary = expect_equal_to_twin(3, 189, {"--discovery-server", "127.0.0.1:11911"});
  EXPECT_EQ(summary["network"]["discovery"], "server 127.0.0.1:11911");
}

}  // namespace
}  // namespace skyfuse::test
