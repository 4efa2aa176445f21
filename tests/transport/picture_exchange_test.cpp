// The picture's exchange over real DDS: three station participants on loopback publish their
// rounds and rebuild every report from what arrives, and each holds, round after round, the
// picture of an in-process peer that fused the stations' own reports, bit for bit.
#include "skyfuse/transport/picture_exchange.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>

#include "skyfuse/transport/picture_round_reports.hpp"
#include "support/process.hpp"
#include "transport/picture_world.hpp"

namespace skyfuse::transport {
namespace {

using namespace std::chrono_literals;
using test::eventually;
using World = test::PictureWorld;
using Exchange = PictureExchange;
// Each test its own domain and run: ctest runs them at once, and a test's stations hearing the
// other's (same ids, same run) once bound the wrong writer to a station and left a round short.
constexpr int kDomain = 97;
constexpr int kForgeryDomain = 93;
constexpr std::uint64_t kRunId = 0x5eed'0000'0097ULL;
constexpr std::size_t kBound = 64;

struct StationNode {
  std::unique_ptr<DdsNode> node;
  std::unique_ptr<Exchange> exchange;
  std::unique_ptr<Reader<wire::PictureScan>> in;
  World::Peer picture;
  PictureRoundReports<World::Tracks> reports;
  std::uint64_t refused = 0;

  // Takes every sample waiting into the exchange.
  void take() {
    wire::PictureScan sample;
    WriterId writer{};
    while (in->take(sample, &writer)) {
      if (writer == exchange->own_writer()) continue;  // publish() kept it, as a station does
      if (exchange->receive(sample, writer)) ++refused;
    }
  }
};

// One participant per station of `world`, each with its exchange and reader of the topic.
std::vector<StationNode> station_nodes(const World& world, int domain = kDomain) {
  std::vector<StationNode> nodes;
  for (const auto& station : world.stations) {
    NodeConfig config;
    config.domain_id = domain;
    config.name = "picture-station-" + std::to_string(station.id);
    auto node = std::make_unique<DdsNode>(config);
    auto exchange = std::make_unique<Exchange>(*node, world.round_stations(), kRunId, kBound);
    auto in = std::make_unique<Reader<wire::PictureScan>>(node->make_reader<wire::PictureScan>());
    nodes.push_back({std::move(node), std::move(exchange), std::move(in), world.empty_picture(),
                     PictureRoundReports<World::Tracks>(world.stations)});
  }
  return nodes;
}

bool all_matched(const std::vector<StationNode>& nodes) {
  return eventually(
      [&] {
        return std::all_of(nodes.begin(), nodes.end(),
                           [](const StationNode& n) { return n.exchange->matched(*n.in); });
      },
      20s);
}

// Until every node holds every station's sample of the current step.
bool all_complete(std::vector<StationNode>& nodes) {
  return eventually(
      [&] {
        bool all = true;
        for (StationNode& n : nodes) {
          n.take();
          all = all && n.exchange->complete();
        }
        return all;
      },
      20s);
}

const auto kNoRefusal = [](int station_id, DropKind why) {
  ADD_FAILURE() << "station " << station_id << "'s sample refused: " << to_string(why);
};

TEST(PictureExchange, ThreeStationsOverLoopbackDdsHoldTheInProcessPictureBitForBit) {
  constexpr int kRounds = 20;
  const World world(kRounds);
  std::vector<StationNode> nodes = station_nodes(world);
  ASSERT_TRUE(all_matched(nodes)) << "the three participants did not match each other";

  World::Peer reference = world.empty_picture();
  AssociationWork work;
  std::size_t associated = 0;
  for (int k = 0; k < kRounds; ++k) {
    const auto own_reports = world.publish_round(nodes, reference, k, work, kRunId);
    ASSERT_TRUE(all_complete(nodes))
        << "round " << k << ": station 1 still misses " << nodes[0].exchange->missing().size();
    reference.fuse(k, own_reports);
    for (StationNode& n : nodes) {
      const auto reports =
          n.reports.reports(*n.exchange, n.picture, n.picture.digest(), kNoRefusal);
      ASSERT_EQ(reports.size(), world.stations.size()) << "round " << k;
      n.picture.fuse(k, reports);
      n.exchange->advance();
      ASSERT_EQ(n.picture.tracks().size(), reference.tracks().size()) << "round " << k;
      EXPECT_EQ(n.picture.digest(), reference.digest()) << "round " << k;
      for (std::size_t t = 0; t < reference.tracks().size(); ++t) {
        EXPECT_EQ(n.picture.tracks()[t].id, reference.tracks()[t].id);
        EXPECT_EQ(n.picture.tracks()[t].status, reference.tracks()[t].status);
        EXPECT_EQ(n.picture.estimates()[t].mean, reference.estimates()[t].mean) << "round " << k;
        EXPECT_EQ(n.picture.estimates()[t].covariance, reference.estimates()[t].covariance);
      }
    }
    for (const auto& report : own_reports) associated += report.updates.size();
  }
  for (const StationNode& n : nodes) {
    EXPECT_EQ(n.refused, 0U);
    EXPECT_EQ(n.reports.other_pictures(), 0U);
  }
  EXPECT_GE(reference.tracks().size(), 5U) << "every aircraft tracked";
  EXPECT_GT(associated, 100U) << "the rounds associated detections to tracks";
}

// A station that sends a scan made against the receivers' own picture (its digest) whose
// association names a track that picture does not hold: no honest station makes one, so every
// receiver leaves it out of the round and says so, and fuses the others'.
TEST(PictureExchange, AScanNamingATrackThePictureDoesNotHoldIsLeftOutAndCounted) {
  constexpr int kRounds = 6;
  const World world(kRounds);
  std::vector<StationNode> nodes = station_nodes(world, kForgeryDomain);
  // The third station publishes through a writer of its own, which forges its last scan.
  Writer<wire::PictureScan> third = nodes[2].node->make_writer<wire::PictureScan>();
  ASSERT_TRUE(all_matched(nodes));
  ASSERT_TRUE(eventually([&] { return third.matched() >= 3; }, 20s));
  AssociationWork work;
  for (int k = 0; k < kRounds; ++k) {
    const auto step = static_cast<std::uint32_t>(k);
    const bool forged = k + 1 == kRounds;
    for (std::size_t s = 0; s < nodes.size(); ++s) {
      StationNode& n = nodes[s];
      n.picture.predict();
      const Scan scan = world.scan(s, k);
      const auto report = n.picture.report(world.stations[s], scan, work);
      wire::PictureScan sample = to_wire<World::Model::kDim>(world.stations[s].sensor, scan, report,
                                                             kRunId, step, n.picture.digest());
      if (s != 2) {
        n.exchange->publish(sample);
        continue;
      }
      if (forged) {
        // A detection of the scan assigned to a track id past every one the picture holds.
        ASSERT_FALSE(sample.associations().empty() && sample.unassociated().empty());
        if (!sample.associations().empty()) {
          sample.associations().back().track_id(~0ULL);
        } else {
          wire::Association a;
          a.track_id(~0ULL);
          a.detection(sample.unassociated().front());
          sample.associations({a});
          sample.unassociated().erase(sample.unassociated().begin());
        }
      }
      third.write(sample);
    }
    ASSERT_TRUE(all_complete(nodes)) << "round " << k;
    for (StationNode& n : nodes) {
      std::vector<int> refused;
      const auto reports = n.reports.reports(*n.exchange, n.picture, n.picture.digest(),
                                             [&](int station_id, DropKind why) {
                                               EXPECT_EQ(why, DropKind::kOutOfRange);
                                               refused.push_back(station_id);
                                             });
      if (forged) {
        EXPECT_EQ(refused, std::vector<int>{world.stations[2].id});
        ASSERT_EQ(reports.size(), 2U);
        EXPECT_NE(reports.back().station_id, world.stations[2].id);
      } else {
        EXPECT_TRUE(refused.empty()) << "round " << k;
        ASSERT_EQ(reports.size(), 3U) << "round " << k;
      }
      n.picture.fuse(k, reports);
      n.exchange->advance();
    }
  }
  EXPECT_EQ(nodes[0].picture.digest(), nodes[1].picture.digest());
  EXPECT_EQ(nodes[0].picture.digest(), nodes[2].picture.digest());
  EXPECT_GT(nodes[0].picture.tracks().size(), 0U);
}

}  // namespace
}  // namespace skyfuse::transport
