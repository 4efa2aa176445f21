// The picture's tree exchange: over real DDS on loopback, three stations in clusters of two
// ({1, 2} aggregated by 1, {3} by itself) hold, round after round, the picture of an in-process
// peer that fused the stations' own reports, bit for bit, each receiving the clusters' bundles
// instead of every station's scan; and the screens refuse every bundle that is not what its
// place in the tree allows, each by its kind.
#include "skyfuse/transport/picture_tree_exchange.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <span>
#include <vector>

#include "skyfuse/transport/picture_round_reports.hpp"
#include "support/process.hpp"
#include "transport/picture_world.hpp"

namespace skyfuse::transport {
namespace {

using namespace std::chrono_literals;
using test::eventually;
using World = test::PictureWorld;
using Exchange = PictureTreeExchange;
constexpr int kDomain = 87;
constexpr std::uint64_t kRunId = 0x5eed'0000'0087ULL;
constexpr std::size_t kBound = 64;

// The sensor kinds of stations `ids`, each a radar as the world's stations are.
StationSensorKinds radars(const World& world, std::span<const int> ids) {
  std::vector<World::Station> stations;
  for (const int id : ids) {
    World::Station station = world.stations.front();
    station.id = id;
    stations.push_back(station);
  }
  return StationSensorKinds(std::span<const World::Station>(stations));
}

ClusterLayout layout_of(const World& world, std::size_t fanout) {
  std::vector<int> ids;
  for (const auto& s : world.stations) ids.push_back(s.id);
  return ClusterLayout(ids, fanout);
}

struct StationNode {
  std::unique_ptr<DdsNode> node;
  std::unique_ptr<Exchange> exchange;
  std::unique_ptr<Reader<wire::PictureBundle>> in;
  World::Peer picture;
  PictureRoundReports<World::Tracks> reports;
  std::uint64_t refused = 0;
  std::uint64_t received = 0;

  // Takes every sample waiting into the exchange, as the round loop does.
  void take() {
    wire::PictureBundle sample;
    WriterId writer{};
    while (in->take(sample, &writer)) {
      if (writer == exchange->own_writer()) continue;
      ++received;
      if (exchange->receive(sample, writer)) ++refused;
    }
  }
};

std::vector<StationNode> station_nodes(const World& world, const ClusterLayout& layout) {
  std::vector<StationNode> nodes;
  for (const auto& station : world.stations) {
    NodeConfig config;
    config.domain_id = kDomain;
    config.name = "picture-tree-station-" + std::to_string(station.id);
    auto node = std::make_unique<DdsNode>(config);
    // The aggregator sends when its members' scans are in: never on the clock here.
    auto in = std::make_unique<Reader<wire::PictureBundle>>(
        node->make_reader<wire::PictureBundle>(Exchange::input_partitions(layout, station.id)));
    auto exchange =
        std::make_unique<Exchange>(*node, world.round_stations(), kRunId, kBound, layout,
                                   station.id, std::chrono::microseconds(30s), in.get());
    nodes.push_back({std::move(node), std::move(exchange), std::move(in), world.empty_picture(),
                     PictureRoundReports<World::Tracks>(world.stations)});
  }
  return nodes;
}

TEST(PictureTreeExchange, ThreeStationsInTwoClustersHoldTheInProcessPictureBitForBit) {
  constexpr int kRounds = 20;
  const World world(kRounds);
  const ClusterLayout layout = layout_of(world, 2);
  ASSERT_EQ(layout.clusters(), 2U);
  std::vector<StationNode> nodes = station_nodes(world, layout);
  // The center hears the clusters' bundles too.
  NodeConfig center_config;
  center_config.domain_id = kDomain;
  center_config.name = "picture-tree-center";
  DdsNode center(center_config);
  Reader<wire::PictureBundle> center_in =
      center.make_reader<wire::PictureBundle>({kPictureClustersPartition});
  std::size_t center_received = 0;
  ASSERT_TRUE(eventually(
      [&] {
        return center_in.matched() >= 2 &&
               std::all_of(nodes.begin(), nodes.end(),
                           [](const StationNode& n) { return n.exchange->matched(*n.in); });
      },
      20s))
      << "the participants did not match as the tree wants";

  World::Peer reference = world.empty_picture();
  AssociationWork work;
  std::size_t associated = 0;
  for (int k = 0; k < kRounds; ++k) {
    const auto own_reports = world.publish_round(nodes, reference, k, work, kRunId);
    ASSERT_TRUE(eventually(
        [&] {
          bool all = true;
          for (StationNode& n : nodes) {
            n.take();
            all = n.exchange->round_complete() && all;
          }
          wire::PictureBundle bundle;
          while (center_in.take(bundle)) ++center_received;
          return all && center_received == 2U * (k + 1);
        },
        20s))
        << "round " << k << ": station 2 still misses " << nodes[1].exchange->missing().size();
    reference.fuse(k, own_reports);
    for (StationNode& n : nodes) {
      ASSERT_EQ(n.exchange->station_count(), 3U);
      const auto reports = n.reports.reports(
          *n.exchange, n.picture, n.picture.digest(),
          [](int id, DropKind why) { ADD_FAILURE() << id << ": " << to_string(why); });
      ASSERT_EQ(reports.size(), world.stations.size()) << "round " << k;
      n.picture.fuse(k, reports);
      n.exchange->advance();
      EXPECT_EQ(n.picture.digest(), reference.digest()) << "round " << k;
    }
    for (const auto& report : own_reports) associated += report.updates.size();
  }
  for (const StationNode& n : nodes) EXPECT_EQ(n.refused, 0U);
  // What each station heard a round: station 1 its member's scan and cluster 1's bundle,
  // station 2 both clusters' bundles, station 3 cluster 0's (its own it keeps).
  EXPECT_EQ(nodes[0].received, 2U * kRounds);
  EXPECT_EQ(nodes[1].received, 2U * kRounds);
  EXPECT_EQ(nodes[2].received, 1U * kRounds);
  EXPECT_EQ(center_received, 2U * kRounds) << "the center: both clusters' bundles a round";
  EXPECT_GE(reference.tracks().size(), 5U) << "every aircraft tracked";
  EXPECT_GT(associated, 100U) << "the rounds associated detections to tracks";
}

// Bundles checked without DDS: stations 1-5 in clusters {1, 2}, {3, 4}, {5}; a cluster's
// bundle comes from its aggregator (the first id) or the aggregator's stand-in (the second).
class PictureBundleScreens : public ::testing::Test {
 protected:
  static constexpr std::uint32_t kStep = 0;

  PictureBundleScreens()
      : world_(2),
        layout_(ids_, 2),
        screen_(layout_, kRunId),
        scans_(ids_, radars(world_, ids_), kRunId, kBound) {}

  // Station `id`'s scan of step 0, as it would send it, against an empty picture.
  wire::PictureScan scan_of(int id) {
    World::Peer picture = world_.empty_picture();
    picture.predict();
    const Scan scan = world_.scan(0, 0);
    auto report = picture.report(world_.stations[0], scan, work_);
    report.station_id = id;
    return to_wire<World::Model::kDim>(world_.stations[0].sensor, scan, report, kRunId, kStep,
                                       picture.digest());
  }
  wire::PictureBundle cluster_bundle(std::uint32_t cluster, int sender, std::vector<int> ids) {
    wire::PictureBundle b;
    b.run_id(kRunId);
    b.step(kStep);
    b.kind(wire::CLUSTER_SCANS);
    b.cluster(cluster);
    b.station_id(sender);
    for (const int id : ids) b.scans().push_back(scan_of(id));
    return b;
  }
  std::optional<DropKind> screen(const wire::PictureBundle& b, std::uint8_t writer = 1) {
    WriterId w{};
    w[0] = writer;
    return screen_.receive(b, w, scans_);
  }

  std::vector<int> ids_ = {1, 2, 3, 4, 5};
  World world_;
  ClusterLayout layout_;
  ClusterBundleScreen screen_;
  PictureScans scans_;
  AssociationWork work_;
};

TEST_F(PictureBundleScreens, AClusterBundleFromItsAggregatorIsUnpackedWhole) {
  EXPECT_EQ(screen(cluster_bundle(1, 3, {3, 4})), std::nullopt);
  EXPECT_NE(scans_.scan_of(3), nullptr);
  EXPECT_NE(scans_.scan_of(4), nullptr);
  EXPECT_EQ(scans_.scan_of(1), nullptr);
  // The same scans again, from the aggregator's stand-in (both relayed while one handed the
  // cluster to the other): each kept once. Another scan for a station already in: refused.
  EXPECT_EQ(screen(cluster_bundle(1, 4, {4}), 2), std::nullopt);
  wire::PictureBundle altered = cluster_bundle(1, 3, {3, 4});
  altered.scans()[1].picture_digest(altered.scans()[1].picture_digest() + 1);
  EXPECT_EQ(screen(altered), DropKind::kDuplicate);
}

TEST_F(PictureBundleScreens, EveryBundleThatIsNotItsAggregatorsIsRefusedByKindAndKeepsNothing) {
  wire::PictureBundle other_run = cluster_bundle(0, 1, {1, 2});
  other_run.run_id(kRunId + 1);
  EXPECT_EQ(screen(other_run), DropKind::kWrongRun);
  wire::PictureBundle member = cluster_bundle(0, 1, {1});
  member.kind(wire::MEMBER_SCAN);
  EXPECT_EQ(screen(member), DropKind::kOutOfRange) << "a member's scan is its aggregator's";
  EXPECT_EQ(screen(cluster_bundle(3, 1, {1})), DropKind::kWrongCluster) << "no cluster 3";
  EXPECT_EQ(screen(cluster_bundle(2, 4, {5})), DropKind::kWrongCluster) << "4 relays no cluster 2";
  EXPECT_EQ(screen(cluster_bundle(1, 5, {3, 4})), DropKind::kWrongCluster) << "nor 5 cluster 1";
  EXPECT_EQ(screen(cluster_bundle(0, 1, {1, 3})), DropKind::kWrongCluster) << "3 is cluster 1's";
  EXPECT_EQ(screen(cluster_bundle(0, 1, {2, 1})), DropKind::kOverlap) << "out of order";
  EXPECT_EQ(screen(cluster_bundle(0, 1, {1, 1})), DropKind::kOverlap) << "a station twice";
  wire::PictureBundle late_scan = cluster_bundle(0, 1, {1, 2});
  late_scan.scans()[1].step(kStep + 1);
  EXPECT_EQ(screen(late_scan), DropKind::kOutOfRange) << "a scan of another step than its bundle";
  wire::PictureBundle wrong_values = cluster_bundle(0, 1, {1, 2});
  wrong_values.scans()[1].values().push_back(1.0);
  EXPECT_EQ(screen(wrong_values), DropKind::kOutOfRange) << "a scan wrong inside";
  EXPECT_EQ(scans_.scan_of(1), nullptr) << "a refused bundle keeps none of its scans";
  // The aggregator speaks through the writer it spoke with first.
  EXPECT_EQ(screen(cluster_bundle(2, 5, {5}), 7), std::nullopt);
  EXPECT_EQ(screen(cluster_bundle(0, 1, {1, 2}), 7), std::nullopt);
  scans_.advance();
  wire::PictureBundle next = cluster_bundle(2, 5, {5});
  next.step(kStep + 1);
  for (auto& s : next.scans()) s.step(kStep + 1);
  EXPECT_EQ(screen(next, 8), DropKind::kDuplicate) << "another writer for aggregator 5";
}

TEST_F(PictureBundleScreens, AnAggregatorTakesOnlyItsOwnMembersScansEachFromItsWriter) {
  // {3, 4}, aggregated by 3.
  ClusterScans cluster(layout_, 1, radars(world_, ids_), kRunId, kBound);
  cluster.keep(scan_of(3));
  EXPECT_FALSE(cluster.complete());
  const auto member = [&](int id, std::uint32_t in_cluster) {
    return member_bundle(scan_of(id), in_cluster);
  };
  WriterId four{};
  four[0] = 4;
  EXPECT_EQ(cluster.receive(member(2, 1), four), DropKind::kWrongCluster) << "2 is cluster 0's";
  EXPECT_EQ(cluster.receive(member(4, 0), four), DropKind::kWrongCluster) << "sent to cluster 0";
  wire::PictureBundle two = member(4, 1);
  two.scans().push_back(scan_of(4));
  EXPECT_EQ(cluster.receive(two, four), DropKind::kOutOfRange) << "a member sends one scan";
  wire::PictureBundle impostor = member(4, 1);
  impostor.station_id(3);
  EXPECT_EQ(cluster.receive(impostor, four), DropKind::kWrongCluster) << "a scan for another";
  EXPECT_EQ(cluster.receive(member(4, 1), four), std::nullopt);
  EXPECT_TRUE(cluster.complete());
  WriterId other{};
  other[0] = 9;
  EXPECT_EQ(cluster.receive(member(4, 1), other), DropKind::kDuplicate);
  const wire::PictureBundle out = cluster.bundle(kStep, 3);
  EXPECT_EQ(out.kind(), wire::CLUSTER_SCANS);
  ASSERT_EQ(out.scans().size(), 2U);
  EXPECT_EQ(out.scans()[0].station_id(), 3);
  EXPECT_EQ(out.scans()[1].station_id(), 4);
  EXPECT_EQ(out.scans()[1], scan_of(4)) << "relayed as its station sent it";
}

}  // namespace
}  // namespace skyfuse::transport
