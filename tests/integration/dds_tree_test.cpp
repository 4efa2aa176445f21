// The tree exchange over DDS: station processes in clusters, each cluster's aggregator summing
// its members' contributions, the aggregators exchanging their sums, every member fusing the
// round's total its aggregator sends.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>

#include "integration/run_fixture.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/tracking/cluster_layout.hpp"

namespace skyfuse::test {
namespace {

using namespace std::chrono_literals;

// A tree run of `scenario` (`stations` in clusters of `fanout`) over DDS: every peer holds the
// same bits, each one the in-process run's with the tree's order of summation (not the flat
// exchange's), central and peer-to-peer within 1e-9 m, nothing refused, no round incomplete.
// Its summary.json. `extra`: more arguments for `skyfuse run`.
nlohmann::json expect_tree_run_equals_twin(const std::string& scenario, int stations, int steps,
                                           int fanout, int domain,
                                           const std::vector<std::string>& extra = {}) {
  const auto dir = test_dir();
  std::vector<std::string> args = {bin("skyfuse"), "run",
                                   "--scenario",   scenario,
                                   "--stations",   std::to_string(stations),
                                   "--steps",      std::to_string(steps),
                                   "--exchange",   "tree",
                                   "--fanout",     std::to_string(fanout),
                                   "--domain",     std::to_string(domain),
                                   "--out",        (dir / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const Completed run = run_to_completion(args, (dir / "out.log").string(), 180s);
  EXPECT_TRUE(run.status.exited && run.status.code == 0) << run.output;
  if (!run.status.exited || run.status.code != 0) return {};

  const auto tracks = read_tracks(dir / "out" / "tracks.csv");
  EXPECT_EQ(tracks.size(), static_cast<std::size_t>(steps * (stations + 1)));
  const Scenario loaded = load_scenario_file(scenario);
  RunOverrides overrides;
  overrides.stations = stations;
  overrides.steps = steps;
  overrides.exchange = ExchangeConfig::Kind::kFlat;
  const RunPlan flat = make_run_plan(loaded, overrides);
  overrides.exchange = ExchangeConfig::Kind::kTree;
  overrides.fanout = fanout;
  const RunPlan plan = make_run_plan(loaded, overrides);
  EXPECT_EQ(difference_from_twin(tracks, plan, in_process_twin(plan)), std::nullopt);
  // The flat exchange sums in another order: its bits are not these, so the run above followed
  // the tree.
  EXPECT_NE(difference_from_twin(tracks, flat, in_process_twin(flat)), std::nullopt);

  auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(summary.at("exchange"), "tree");
  EXPECT_EQ(summary.at("max_abs_diff_between_peers"), 0.0);
  EXPECT_LT(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 1e-9);
  EXPECT_EQ(summary.at("rounds_closed_incomplete"), 0);
  for (const auto& [kind, count] : summary.at("dropped_by_kind").items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
  return summary;
}

// With default options 16 stations share 4 processes (Placement::auto_stations_per_process);
// the bits are those of the in-process tree all the same.
TEST(DdsTree, SixteenStationsInClustersOfFourEqualTheInProcessTreeBitForBit) {
  const auto summary = expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 16, 200, 4, 208);
  ASSERT_FALSE(summary.is_null());
  EXPECT_EQ(summary.at("network").at("stations_per_process").get<int>(), 4);
}

// `--discovery peers`: each process announces itself only to those it exchanges samples with.
// The run is the same bit for bit, and each node reports knowing only its partners: the
// harness and the center, its 3 cluster mates, and for a cluster's first two members (the
// aggregator and its stand-in) the first two of each of the 3 other clusters. The center knows
// the harness and every station. With multicast discovery every node knows all 17 others.
TEST(DdsTree, StationsDiscoveringOnlyTheirPeersKnowTheirClusterAndGiveTheInProcessTreesBits) {
  // One process a station, as the counts below are of processes (16 stations would otherwise
  // share 4 by default).
  const auto summary =
      expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 16, 200, 4, 221,
                                  {"--discovery", "peers", "--stations-per-process", "1"});
  ASSERT_FALSE(summary.is_null());
  const auto& network = summary.at("network");
  EXPECT_EQ(network.at("discovery"), "peers");
  const auto& known = network.at("participants_known_by_node");
  EXPECT_EQ(known.at("center").get<int>(), 1 + 16);
  for (int id = 1; id <= 16; ++id) {
    const bool stand_in = (id - 1) % 4 < 2;
    EXPECT_EQ(known.at(std::to_string(id)).get<int>(), stand_in ? 2 + 3 + 2 * 3 : 2 + 3)
        << "station " << id;
  }
}

// `--stations-per-process 4`: each cluster of 4 stations in one process, sharing its participant
// (its samples pass in memory). The wire and the results are those of one process per station:
// the in-process tree's bits. Each process holds an aggregator and its stand-in, so it knows the
// harness, the center and the 3 other processes; the center knows the harness and the 4.
TEST(DdsTree, StationsSharingAProcessGiveTheInProcessTreesBits) {
  const auto summary =
      expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 16, 200, 4, 61,
                                  {"--discovery", "peers", "--stations-per-process", "4"});
  ASSERT_FALSE(summary.is_null());
  const auto& network = summary.at("network");
  EXPECT_EQ(network.at("stations_per_process"), 4);
  const auto& known = network.at("participants_known_by_node");
  EXPECT_EQ(known.at("center").get<int>(), 1 + 4);
  for (int id = 1; id <= 16; ++id) {
    EXPECT_EQ(known.at(std::to_string(id)).get<int>(), 2 + 3) << "station " << id;
  }
}

// What several stations in one process cannot do is refused before anything starts, naming why:
// a kill would take the process's every station, and DDS-Security authenticates a participant.
TEST(DdsTree, StationsSharingAProcessRefuseKillsAndASecureStation) {
  const auto dir = test_dir();
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--stations", "4", "--steps", "20", "--stations-per-process", "2",
       "--kill", "2@5", "--domain", "62", "--out", (dir / "out").string()},
      dir / "run.log", 60s);
  EXPECT_EQ(run.status.code, 2) << run.output;
  EXPECT_THAT(run.output, ::testing::HasSubstr("--stations-per-process: not with --kill"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json"));

  const Completed station = run_to_completion({bin("skyfuse-station"), "--id", "1", "--id", "2",
                                               "--secure", dir.string(), "--domain", "62"},
                                              dir / "station.log", 60s);
  EXPECT_EQ(station.status.code, 2) << station.output;
  EXPECT_THAT(station.output, ::testing::HasSubstr("several --id with --secure"));
  const Completed twice = run_to_completion(
      {bin("skyfuse-station"), "--id", "1", "--id", "1", "--domain", "62"}, dir / "twice.log", 60s);
  EXPECT_EQ(twice.status.code, 2) << twice.output;
  EXPECT_THAT(twice.output, ::testing::HasSubstr("an id given twice"));
}

// `--discovery auto` (the default) picks peers for a tree of 16 on a domain whose ports lie
// below the kernel's ephemeral range, and the run still equals the in-process tree bit for bit;
// on a domain in that range it keeps multicast.
TEST(DdsTree, AutoDiscoveryTakesPeersForALargeTreeOnALowDomain) {
  const auto low = expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 16, 100, 4, 67);
  ASSERT_FALSE(low.is_null());
  EXPECT_EQ(low.at("network").at("discovery"), "peers");
  const auto high = expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 16, 50, 4, 227);
  ASSERT_FALSE(high.is_null());
  EXPECT_EQ(high.at("network").at("discovery"), "multicast");
}

// Peer discovery fixes every participant's ports: one held by another socket would leave that
// participant unannounced and the run timing out in discovery. The run refuses before it
// starts, naming the port.
TEST(DdsTree, PeerDiscoveryRefusesAPortAnotherSocketHolds) {
  constexpr int kDomain = 226;
  // The RTPS well-known discovery port of participant 3 (the second station): 7400 + 250 d +
  // 10 + 2 id.
  const std::uint16_t port = 7400 + 250 * kDomain + 10 + 2 * 3;
  const int holder = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(holder, 0);
  sockaddr_in where{};
  where.sin_family = AF_INET;
  where.sin_port = htons(port);
  where.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(holder, reinterpret_cast<const sockaddr*>(&where), sizeof(where)), 0);
  const auto dir = test_dir();
  const Completed run = run_to_completion(
      {bin("skyfuse"), "run", "--scenario", bin("scenarios/ring64.yaml"), "--stations", "16",
       "--exchange", "tree", "--fanout", "4", "--discovery", "peers", "--steps", "5", "--domain",
       std::to_string(kDomain), "--out", (dir / "out").string()},
      dir / "run.log", 60s);
  ::close(holder);
  EXPECT_EQ(run.status.code, 2) << run.output;
  EXPECT_THAT(run.output, ::testing::HasSubstr("UDP port " + std::to_string(port) +
                                               " on 127.0.0.1 (participant 3 of domain 226"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.json"));
}

// The IMM over the tree (paper 000's ten stations in clusters of 3, the last cluster of one,
// through the turn at 10-18 s): each sum carries every mode's increments and likelihood terms,
// one sample per mode; peers agree in the mode probabilities too.
TEST(DdsTree, AnImmsModesAreSummedByTheTreeAsTheInProcessRunSumsThem) {
  const auto summary =
      expect_tree_run_equals_twin(bin("scenarios/paper000-imm.yaml"), 10, 1000, 3, 216);
  if (HasFailure()) return;
  EXPECT_EQ(summary.at("filter"), "imm");
  EXPECT_LT(summary.at("max_abs_diff_mode_probability_central_vs_p2p").get<double>(), 1e-9);
}

// Paper 002's NCRKF over the tree (its three TDOA receivers in clusters of 2): each sum carries
// its fallback without the indefinite increments; every peer and the center hold the same bits.
TEST(DdsTree, TheNcrkfsSumsAndTheirFallbackGiveTheInProcessTreesBits) {
  const auto summary = expect_tree_run_equals_twin(bin("scenarios/paper002.yaml"), 3, 2000, 2, 219);
  if (HasFailure()) return;
  EXPECT_EQ(summary.at("max_abs_diff_central_vs_p2p").get<double>(), 0.0);
}

// Delayed links (2 +- 1 ms on every sample, three hops a round) change when samples come, not
// what is summed: the in-process tree's bits.
TEST(DdsTree, DelayedLinksLeaveEveryPeerWithTheInProcessTreesBits) {
  expect_tree_run_equals_twin(bin("scenarios/ring64.yaml"), 8, 100, 4, 217,
                              {"--link-delay-ms", "2", "--link-jitter-ms", "1"});
}

// 5 % of the samples lost on every link for 100 rounds: a member whose total was lost fuses its
// own contribution alone and an aggregator that lost a cluster's sum fuses the rest, so peers
// disagree during the loss; each round is fused onto its total's reference, so they hold the
// same bits again once a round is whole, and no lost total is taken for a dead aggregator
// (no cluster taken over: nothing refused as wrong_cluster).
TEST(DdsTree, PeersThatLostSumsAgreeAgainAfterTheLossWithoutTakingClustersOver) {
  constexpr int kSteps = 300;
  const auto dir = test_dir();
  const Completed run = run_to_completion({bin("skyfuse"),
                                           "run",
                                           "--scenario",
                                           bin("scenarios/ring64.yaml"),
                                           "--stations",
                                           "8",
                                           "--steps",
                                           std::to_string(kSteps),
                                           "--exchange",
                                           "tree",
                                           "--fanout",
                                           "4",
                                           "--loss",
                                           "0.05",
                                           "--loss-steps",
                                           "100:200",
                                           "--round-deadline-ms",
                                           "50",
                                           "--domain",
                                           "218",
                                           "--out",
                                           (dir / "out").string()},
                                          (dir / "out.log").string(), 180s);
  ASSERT_EQ(run.status.code, 0) << run.output;
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_GT(summary.at("max_abs_diff_between_peers").get<double>(), 0.0)
      << "peers that lost different samples cannot agree during the loss";
  EXPECT_EQ(summary.at("dropped_by_kind").at("wrong_cluster").get<int>(), 0);
  const auto spread = steps_column(dir / "out" / "steps.csv", "peer_spread");
  const auto apart = steps_column(dir / "out" / "steps.csv", "central_minus_p2p_m");
  ASSERT_EQ(spread.size(), static_cast<std::size_t>(kSteps));
  for (int k = 201; k < kSteps; ++k) EXPECT_EQ(spread[k], 0.0) << "step " << k;
  // The center lost other measurements than the peers: they drift together again slowly.
  for (int k = 250; k < kSteps; ++k) EXPECT_LT(apart[k], 1e-4) << "step " << k;
}

// Cluster 0's aggregator (station 1) killed before round 100 and started again before round
// 150: its members and the other aggregators hear nothing from it in round 100, so from round
// 101 station 2, the next id of the cluster, aggregates in its place (it moves its endpoints
// into the aggregator's partitions); the restarted station 1 sends its cluster's sum again, the
// others hear a lower id than station 2 and take it back, and station 2 gives the cluster back.
// Peers disagree only in the round of each change and the one after: every other round holds
// the same bits on every peer, and nothing is counted twice (peer-to-peer stays within 1e-4 m
// of the center).
void expect_aggregator_replaced_and_restored(int domain, const std::vector<std::string>& extra) {
  constexpr int kSteps = 300;
  constexpr int kStations = 16;
  constexpr std::size_t kFanout = 4;
  const auto dir = test_dir();
  std::vector<std::string> args = {
      bin("skyfuse"), "run", "--scenario", bin("scenarios/ring64.yaml"), "--stations",
      std::to_string(kStations), "--steps", std::to_string(kSteps), "--exchange", "tree",
      "--fanout", std::to_string(kFanout),
      // Long enough that no total comes late under a loaded suite (at 50 ms one round in 300
      // did, and its member fused alone; at 250 ms, in a full -j2 suite on the EPYC, members
      // fused late totals apart in rounds 154-160, up to 1.16 m); only the rounds of the kill
      // and the restart wait for it.
      "--round-deadline-ms", "1000", "--kill", "1@100", "--restart", "1@150", "--domain",
      std::to_string(domain), "--out", (dir / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const Completed run = run_to_completion(args, (dir / "out.log").string(), 180s);
  ASSERT_EQ(run.status.code, 0) << run.output;
  EXPECT_EQ(run.output.find("was killed by signal"), std::string::npos) << run.output;

  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  // Station 1 rejoins in round 151 once its readers match the writers it needs in round 150;
  // the harness waits for one of them only (the cluster may have another aggregator by now),
  // and on a CI machine starved by a parallel suite the rest matched three rounds later (154).
  // Either way it is missing from the kill to the rejoin, and from no other round.
  const int rejoin = summary["rejoin_step_by_station"]["1"].get<int>();
  EXPECT_GE(rejoin, 151);
  EXPECT_LE(rejoin, 160);
  EXPECT_EQ(summary["rounds_missing_by_station"]["1"].get<int>(), rejoin - 100);

  const auto spread = steps_column(dir / "out" / "steps.csv", "peer_spread");
  const auto apart = steps_column(dir / "out" / "steps.csv", "central_minus_p2p_m");
  ASSERT_EQ(spread.size(), static_cast<std::size_t>(kSteps));
  const auto changing = [&](int k) {
    return k == 100 || k == 101 || (k >= 150 && k <= rejoin + 2);
  };
  for (int k = 0; k < kSteps; ++k) {
    // Peers disagree in the rounds of a change: the kill's, and from the restart to the
    // rejoin's next (151-152 on an idle machine). While a late rejoin is pending, members that
    // already hear station 1 send to it and the others to station 2, so cluster 0's sum misses
    // some contributions (a full -j2 suite on the EPYC: rejoin late, peers apart in rounds
    // 152-162, central vs p2p up to 0.18 m at round 160, then together again).
    if (!changing(k)) {
      EXPECT_EQ(spread[k], 0.0) << "step " << k;
    }
    // After a fault the center and the peers hold different histories, and drift together
    // again only slowly (the flat exchange too: about 1e-7 m a hundred rounds after a station's
    // restart); a station counted twice would set them millimetres apart.
    const bool settling = (k >= 100 && k < 110) || (k >= 150 && k < rejoin + 10);
    if (!settling) {
      EXPECT_LT(apart[k], 1e-4) << "step " << k;
    }
  }
  // Every other station misses at most the kill's round and the restart's. Station 1's
  // cluster-mates (clusters of kFanout by id: 2-4) may miss any round of a change, the rounds
  // where peers may disagree above: 100 and 101 while station 2 takes over, and 150 to two
  // after the rejoin while some send to station 1 and some to station 2 (CI, a full -j2 suite:
  // station 3 missed 3 rounds; on an idle machine they miss at most one).
  int change_rounds = 0;
  for (int k = 0; k < kSteps; ++k) change_rounds += changing(k) ? 1 : 0;
  std::vector<int> ids(kStations);
  std::iota(ids.begin(), ids.end(), 1);
  const ClusterLayout clusters(ids, kFanout);
  for (const auto& [station, rounds] : summary["rounds_missing_by_station"].items()) {
    const int id = std::stoi(station);
    if (id == 1) continue;
    const bool cluster_mate = clusters.cluster_of_id(id) == clusters.cluster_of_id(1);
    EXPECT_LE(rounds.get<int>(), cluster_mate ? change_rounds : 2)
        << "station " << station << ", rejoin at " << rejoin;
  }
}

TEST(DdsTree, AKilledAggregatorIsReplacedByTheNextIdAndTakesItsClusterBackWhenRestarted) {
  expect_aggregator_replaced_and_restored(210, {});
}

// With peer discovery the stand-in (station 2) already knows the other clusters' aggregators,
// and the restarted station 1 announces itself to its peers again.
TEST(DdsTree, AnAggregatorsStandInTakesOverWhenStationsDiscoverOnlyTheirPeers) {
  expect_aggregator_replaced_and_restored(222, {"--discovery", "peers"});
}

std::vector<std::string> tree_run_args(int domain, const std::filesystem::path& out) {
  return {bin("skyfuse"), "run",
          "--stations",   "8",
          "--steps",      "60",
          "--exchange",   "tree",
          "--fanout",     "4",
          "--run-id",     "8087",
          "--domain",     std::to_string(domain),
          "--out",        out.string()};
}

// A rogue inside the domain sends, at three steps, a partial sum of every malformed kind on each
// of the tree's channels: to cluster 0's aggregator (station 1) as its member 2, to both
// aggregators (1 and 5) as cluster 1's aggregator, to cluster 0's members (2, 3, 4) as their
// aggregator; and its malformed measurements to the center and the harness. Nothing it sends
// is fused - the tracks are the clean run's bytes - and every receiver counts each kind.
TEST(DdsTree, RoguePartialSumsAreRefusedAndCountedByKind) {
  const auto dir = test_dir();
  constexpr int kDomain = 209;
  const Completed clean =
      run_to_completion(tree_run_args(kDomain, dir / "clean"), dir / "clean.log", 120s);
  ASSERT_EQ(clean.status.code, 0) << clean.output;

  Process attacked(tree_run_args(kDomain, dir / "attacked"), dir / "attacked.log");
  const Completed rogue =
      run_to_completion({bin("skyfuse-rogue"), "--domain", std::to_string(kDomain), "--run-id",
                         "8087", "--stations", "8", "--victim", "1", "--tree", "4"},
                        dir / "rogue.log", 120s);
  const std::optional<ExitStatus> status = attacked.wait(120s);
  ASSERT_TRUE(status.has_value()) << attacked.output();
  ASSERT_EQ(status->code, 0) << attacked.output();
  ASSERT_EQ(rogue.status.code, 0) << rogue.output;
  // Seven kinds on three channels, overlap on two, at three steps.
  EXPECT_THAT(rogue.output, ::testing::HasSubstr("sent partial sum non_finite 9"));
  EXPECT_THAT(rogue.output, ::testing::HasSubstr("sent partial sum wrong_cluster 9"));
  EXPECT_THAT(rogue.output, ::testing::HasSubstr("sent partial sum overlap 6"));

  EXPECT_EQ(read_file(dir / "attacked" / "tracks.csv"), read_file(dir / "clean" / "tracks.csv"));
  const auto clean_summary = nlohmann::json::parse(read_file(dir / "clean" / "summary.json"));
  for (const auto& [kind, count] : clean_summary["dropped_by_kind"].items()) {
    EXPECT_EQ(count.get<int>(), 0) << kind;
  }
  const auto summary = nlohmann::json::parse(read_file(dir / "attacked" / "summary.json"));
  const auto& by_kind = summary["dropped_by_kind"];
  constexpr int kSteps = 3;
  // Receivers: 1 on the way up, 2 aggregators, 3 members on the way down; the measurements' 2.
  for (const char* kind : {"wrong_run", "future_step", "non_finite", "not_positive"}) {
    EXPECT_EQ(by_kind[kind].get<int>(), kSteps * (1 + 2 + 3 + 2)) << kind;
  }
  EXPECT_EQ(by_kind["wrong_cluster"].get<int>(), kSteps * (1 + 2 + 3));
  EXPECT_EQ(by_kind["overlap"].get<int>(), kSteps * (2 + 3));
  EXPECT_EQ(by_kind["unknown_station"].get<int>(), kSteps * 2);
  // Each channel's impersonation (its sender's well-formed sample for step k + 1 from the
  // rogue's writer) and its stale sample are one each of duplicate and stale_step per receiver
  // and step, whichever of the two the impersonation turned out (see dds_rogue_test.cpp).
  const std::map<std::string, int> channels_heard = {
      {"1", 2}, {"2", 1}, {"3", 1}, {"4", 1},      {"5", 1},
      {"6", 0}, {"7", 0}, {"8", 0}, {"center", 1}, {"harness", 1}};
  for (const auto& [node, channels] : channels_heard) {
    const auto& counts = summary["dropped_by_node"].at(node);  // empty if nothing was refused
    EXPECT_EQ(counts.value("duplicate", 0) + counts.value("stale_step", 0), 2 * kSteps * channels)
        << node;
  }
}

}  // namespace
}  // namespace skyfuse::test
