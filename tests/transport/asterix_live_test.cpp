// A station's live feed (transport/asterix_live.hpp) over this host's loopback: the records of
// its own data source, sent as a sensor would, come back as the quantised scans they were made
// of; a round is taken at once when the feed has passed it, after the wait when it has not; a
// record of a round already taken is late, counted and not fused.
#include "skyfuse/transport/asterix_live.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "skyfuse/asterix/cat048.hpp"
#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/traffic/traffic_truth.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

namespace skyfuse::transport {
namespace {

using namespace std::chrono_literals;

// Station `s` (index)'s scan of round k as the datagrams a sensor would send.
std::vector<asterix::Bytes> datagrams_of(const Scenario& scenario, const SimulatedScan& scan,
                                         std::size_t s, int k) {
  const ScanRecords records =
      scan_records(scan, scenario.stations[s], k * scenario.time_step_s, scenario);
  std::optional<asterix::EncodeError> error;
  auto blocks =
      asterix::encode_blocks(records.category, records.records, asterix::kMaxUdpPayload, error);
  EXPECT_FALSE(error.has_value());
  return blocks;
}

// Polls `done` for up to 10 s: what a datagram on its way through the loopback takes.
template <typename Done>
bool eventually(Done done) {
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  while (!done() && std::chrono::steady_clock::now() < give_up) std::this_thread::sleep_for(1ms);
  return done();
}

TEST(LiveScans, TakeTheRoundsOfTheFeedAsTheQuantisedScansAndCountWhatCameLate) {
  Scenario scenario =
      load_scenario_file(std::string(SKYFUSE_BIN_DIR) + "/scenarios/uam-mixed.yaml");
  scenario.asterix.sac = 25;  // this network's area: another's records are not this station's
  const auto truth = build_traffic_truth(scenario).targets;
  constexpr int kStations = 10;
  constexpr int kFirst = 20;      // the aircraft appear over the first minute
  constexpr std::size_t kMe = 6;  // station 7, a Mode S radar
  const StationConfig& me = scenario.stations[kMe];
  ASSERT_EQ(me.sensor.kind, "range_azimuth_altitude");

  LiveScans live(asterix::UdpEndpoint{{127, 0, 0, 1}, 0}, 300ms, scenario, me);
  asterix::UdpSender sender(asterix::UdpEndpoint{{127, 0, 0, 1}, live.port()});
  // The buffer it asked for, as far as the system lets a process have one.
  std::size_t system_limit = 0;
  std::ifstream("/proc/sys/net/core/rmem_max") >> system_limit;
  if (system_limit > 0) {
    EXPECT_EQ(live.receive_buffer(), std::min(LiveScans::kReceiveBufferOctets, system_limit));
  }
  std::vector<std::vector<SimulatedScan>> rounds;
  for (int k = kFirst; k < kFirst + 5; ++k) {
    rounds.push_back(simulated_scans_at(scenario, truth, kStations, 0, k));
  }
  std::size_t sent = 0;
  const auto send = [&](int k, std::size_t s, const Scenario& from) {
    const auto datagrams =
        datagrams_of(from, rounds[static_cast<std::size_t>(k - kFirst)][s], s, k);
    EXPECT_FALSE(datagrams.empty()) << "station index " << s << " round " << k;
    for (const asterix::Bytes& d : datagrams) EXPECT_TRUE(sender.send(d));
    sent += datagrams.size();
  };
  const auto expected = [&](int k) {
    return *quantised_as_asterix(rounds[static_cast<std::size_t>(k - kFirst)][kMe],
                                 scenario.stations[kMe], scenario);
  };
  const auto same = [](const Scan& a, const Scan& b) {
    if (a.detections.size() != b.detections.size() || a.addresses != b.addresses) return false;
    for (std::size_t j = 0; j < a.detections.size(); ++j) {
      if (!same_detection(a.detections[j], b.detections[j])) return false;
    }
    return true;
  };

  // Rounds kFirst and kFirst + 1 sent: the first is passed, taken at once, the whole of it.
  send(kFirst, kMe, scenario);
  send(kFirst + 1, kMe, scenario);
  const DetectionNoise noise = rounds[0][kMe].scan.noise;
  const Scan first = live.scan_at(kFirst, noise);
  EXPECT_GT(first.detections.size(), 3U);
  EXPECT_TRUE(same(first, expected(kFirst)));
  EXPECT_EQ(first.station_id, me.id);
  EXPECT_EQ(live.waited_out(), 0U);

  // Nothing has passed kFirst + 1: the station waits, then takes what came — all of it here.
  const Scan second = live.scan_at(kFirst + 1, noise);
  EXPECT_TRUE(same(second, expected(kFirst + 1)));
  EXPECT_EQ(live.waited_out(), 1U);

  // Round kFirst again, after it was taken: late, every record of it.
  send(kFirst, kMe, scenario);
  EXPECT_TRUE(eventually([&] { return live.late() == expected(kFirst).detections.size(); }))
      << live.late();

  // Another network's area (SAC 0) on the same group: its records under this station's SIC are
  // not this station's, and its later rounds pass none of this network's: the station waits.
  Scenario elsewhere = scenario;
  elsewhere.asterix.sac = 0;
  send(kFirst + 2, kMe, elsewhere);
  send(kFirst + 3, 8, elsewhere);
  ASSERT_TRUE(eventually([&] { return live.datagrams() == sent; })) << live.summary();
  const Scan third = live.scan_at(kFirst + 2, noise);
  EXPECT_TRUE(third.detections.empty());
  EXPECT_EQ(live.waited_out(), 2U);

  // This network's station 9 (a Remote ID receiver) at kFirst + 4 passes kFirst + 3, of which
  // nothing of this station came: an empty scan, taken without the wait.
  send(kFirst + 4, 8, scenario);
  ASSERT_TRUE(eventually([&] { return live.datagrams() == sent; })) << live.summary();
  const Scan fourth = live.scan_at(kFirst + 3, noise);
  EXPECT_TRUE(fourth.detections.empty());
  EXPECT_EQ(live.waited_out(), 2U);
  EXPECT_NE(live.summary().find("station 7's live feed"), std::string::npos) << live.summary();
  EXPECT_NE(live.started().find("waiting at most 300 ms"), std::string::npos) << live.started();
}

TEST(LiveScans, RefuseASensorNoItemCarriesAndAStationPastSic) {
  Scenario scenario;
  scenario.time_step_s = 1.0;
  StationConfig station;
  station.id = 1;
  station.sensor.kind = "multilateration";
  const asterix::UdpEndpoint any_port{{127, 0, 0, 1}, 0};
  EXPECT_THROW(LiveScans(any_port, 10ms, scenario, station), std::invalid_argument);
  station.sensor.kind = "range_azimuth_altitude";
  station.id = 256;
  EXPECT_THROW(LiveScans(any_port, 10ms, scenario, station), std::invalid_argument);
}

}  // namespace
}  // namespace skyfuse::transport
