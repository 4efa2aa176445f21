// The picture's exchange over real DDS: three station participants on loopback publish their
// rounds and rebuild every report from what arrives, and each holds, round after round, the
// picture of an in-process peer that fused the stations' own reports, bit for bit.
#include "skyfuse/transport/picture_exchange.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>

#include "support/process.hpp"
#include "transport/picture_world.hpp"

namespace skyfuse::transport {
namespace {

using namespace std::chrono_literals;
using test::eventually;
using World = test::PictureWorld;
using Exchange = PictureExchange<World::Tracks, World::Sensor>;
constexpr int kDomain = 97;
constexpr std::uint64_t kRunId = 0x5eed'0000'0097ULL;
constexpr std::size_t kBound = 64;

struct StationNode {
  std::unique_ptr<DdsNode> node;
  std::unique_ptr<Exchange> exchange;
  std::unique_ptr<Reader<wire::PictureScan>> in;
  World::Peer picture;
  std::uint64_t refused = 0;

  // Takes every sample waiting into the exchange.
  void take() {
    wire::PictureScan sample;
    WriterId writer{};
    while (in->take(sample, &writer)) {
      if (exchange->receive(sample, writer)) ++refused;
    }
  }
};

TEST(PictureExchange, ThreeStationsOverLoopbackDdsHoldTheInProcessPictureBitForBit) {
  constexpr int kRounds = 20;
  const World world(kRounds);
  std::vector<StationNode> nodes;
  for (const auto& station : world.stations) {
    NodeConfig config;
    config.domain_id = kDomain;
    config.name = "picture-station-" + std::to_string(station.id);
    auto node = std::make_unique<DdsNode>(config);
    auto exchange = std::make_unique<Exchange>(*node, world.stations, kRunId, kBound);
    auto in = std::make_unique<Reader<wire::PictureScan>>(node->make_reader<wire::PictureScan>());
    nodes.push_back({std::move(node), std::move(exchange), std::move(in), world.empty_picture()});
  }
  ASSERT_TRUE(eventually(
      [&] {
        return std::all_of(nodes.begin(), nodes.end(),
                           [](const StationNode& n) { return n.exchange->matched(*n.in); });
      },
      20s))
      << "the three participants did not match each other";

  World::Peer reference = world.empty_picture();
  AssignmentWork work;
  std::size_t associated = 0;
  for (int k = 0; k < kRounds; ++k) {
    const auto step = static_cast<std::uint32_t>(k);
    reference.predict();
    std::vector<World::Peer::Report> own_reports;
    for (std::size_t s = 0; s < nodes.size(); ++s) {
      StationNode& n = nodes[s];
      n.picture.predict();
      const Scan<3> scan = world.scan(s, k);
      own_reports.push_back(reference.report(world.stations[s], scan, work));
      n.exchange->publish(step, scan, n.picture.report(world.stations[s], scan, work),
                          n.picture.digest());
    }
    ASSERT_TRUE(eventually(
        [&] {
          bool all = true;
          for (StationNode& n : nodes) {
            n.take();
            all = all && n.exchange->complete();
          }
          return all;
        },
        20s))
        << "round " << k << ": station 1 still misses " << nodes[0].exchange->missing().size();
    reference.fuse(k, own_reports);
    for (StationNode& n : nodes) {
      const auto reports = n.exchange->reports(n.picture);
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
    EXPECT_EQ(n.exchange->other_pictures(), 0U);
  }
  EXPECT_GE(reference.tracks().size(), 5U) << "every aircraft tracked";
  EXPECT_GT(associated, 100U) << "the rounds associated detections to tracks";
}

}  // namespace
}  // namespace skyfuse::transport
