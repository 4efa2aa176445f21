// Many aircraft, one picture, in one process: M peers that each assign only their own station's
// scan and fuse everyone's reports hold the same picture bit for bit every round, and the
// center, which runs the same rule on the raw scans, makes the same associations and holds the
// same states to rounding.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <variant>
#include <vector>

#include "skyfuse/metrics/gospa.hpp"
#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/central_picture.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"
#include "unit/picture/picture_round.hpp"

namespace skyfuse {
namespace {

using Model = ConstantVelocity3D;
using TrackSensor = RangeAzimuthElevation<Model::kDim>;
using TruthSensor = RangeAzimuthElevation<kKinematicsDim>;
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using CenterTracks = CenterStackedTracks<Model>;
using Peer = PeerPicture<PeerTracks>;
using Center = CentralPicture<CenterTracks>;
using Station = KnownStation<Model::kDim>;

constexpr double kTimeStepS = 1.0;
constexpr std::uint64_t kSeed = 2026;

// Straight, level flights over a 10 km square at UAM speeds; some appear late, one leaves.
std::vector<TargetTruth> straight_flights(int steps) {
  struct Flight {
    Vector3 start;
    Vector3 velocity;
    int first;
    int last;
  };
  const std::vector<Flight> flights = {
      {{-4000, -3000, 300}, {40, 10, 0}, 0, steps}, {{3000, 4000, 450}, {-20, -45, 0}, 0, steps},
      {{-2000, 3500, 250}, {35, -30, 1}, 5, steps}, {{4500, -4000, 600}, {-50, 0, 0}, 10, 70},
      {{0, -4500, 350}, {0, 55, -1}, 20, steps},
  };
  std::vector<TargetTruth> truths;
  for (std::size_t f = 0; f < flights.size(); ++f) {
    TargetTruth truth{fmt::format("T{}", f), flights[f].first, {}};
    for (int k = flights[f].first; k < flights[f].last; ++k) {
      Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
      x.head<3>() = flights[f].start + (k - flights[f].first) * kTimeStepS * flights[f].velocity;
      x.segment<3>(3) = flights[f].velocity;
      truth.states.push_back(x);
    }
    truths.push_back(truth);
  }
  return truths;
}

std::vector<Station> radars() {
  const std::vector<Vector3> sites = {
      {-6000, -6000, 30}, {6000, -6000, 45}, {6000, 6000, 20}, {-6000, 6000, 60}};
  Covariance<3> noise = Covariance<3>::Zero();
  noise.diagonal() << 5.0 * 5.0, std::pow(0.2 * std::numbers::pi / 180.0, 2),
      std::pow(0.2 * std::numbers::pi / 180.0, 2);
  std::vector<Station> stations;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    stations.push_back({static_cast<int>(i + 1), TrackSensor(sites[i]), noise, 1.0, {}});
  }
  return stations;
}

DetectionConfig detection() {
  DetectionConfig config;
  config.probability = 0.9;
  config.field_of_view.max_range_m = 20000.0;
  config.field_of_view.min_elevation_rad = 0.0;
  config.clutter_per_scan = 5.0;
  return config;
}

template <typename State>
void expect_same_bits(std::span<const Track<State>> a, std::span<const Track<State>> b, int step) {
  ASSERT_EQ(a.size(), b.size()) << "step " << step;
  for (std::size_t t = 0; t < a.size(); ++t) {
    EXPECT_EQ(a[t].id, b[t].id) << "step " << step;
    EXPECT_EQ(a[t].status, b[t].status);
    EXPECT_EQ(a[t].history, b[t].history);
    EXPECT_EQ(a[t].updated_by, b[t].updated_by);
    // Bit for bit: operator== on doubles.
    EXPECT_TRUE(a[t].filter.mean == b[t].filter.mean) << "step " << step;
    EXPECT_TRUE(a[t].filter.covariance == b[t].filter.covariance) << "step " << step;
  }
}

TEST(PictureNetwork, PeersHoldOnePictureAndTheCenterAgrees) {
  constexpr int kSteps = 100;
  const std::vector<TargetTruth> truths = straight_flights(kSteps);
  const std::vector<Station> stations = radars();
  const Model motion(kTimeStepS, {0.5, 1.0});
  Vector<Model::kDim> initial_variance = Vector<Model::kDim>::Constant(100.0);
  const TrackerConfig config;
  std::vector<Peer> peers(stations.size(),
                          Peer(PeerTracks(motion, initial_variance), stations, config));
  Center center(CenterTracks(motion, initial_variance), stations, config);
  const DetectionConfig sees = detection();

  std::size_t compared_associations = 0;
  std::size_t clutter_detections = 0;
  double worst_state_gap = 0.0;
  Gospa last{};
  for (int k = 0; k < kSteps; ++k) {
    const auto step = static_cast<std::uint64_t>(k);
    std::vector<Scan> scans;
    for (const auto& station : stations) {
      ScanOrigins origins;
      const Vector3 site = std::get<TrackSensor>(station.sensor).site();
      scans.push_back(simulate_scan(station.id, TruthSensor(site), site,
                                    fixed_noise<3>(station.noise), sees, truths, k, kSeed, 0,
                                    &origins));
      for (const int o : origins.target) clutter_detections += o < 0 ? 1 : 0;
    }
    // Each station reports against its own peer's predicted picture.
    const std::vector<Peer::Report> reports = test::play_picture_round(
        step, peers, center, std::span<const Station>(stations), std::span<const Scan>(scans));

    for (std::size_t p = 1; p < peers.size(); ++p) {
      expect_same_bits(peers[0].tracks(), peers[p].tracks(), k);
    }
    std::vector<Association> peer_associations;
    for (const auto& report : reports) {
      for (const ReportedPair& pair : report.pairs) {
        peer_associations.push_back({report.station_id, pair.detection, pair.track});
      }
    }
    ASSERT_EQ(peer_associations, center.associations()) << "step " << k;
    compared_associations += peer_associations.size();
    ASSERT_EQ(peers[0].tracks().size(), center.tracks().size()) << "step " << k;
    for (std::size_t t = 0; t < center.tracks().size(); ++t) {
      ASSERT_EQ(peers[0].tracks()[t].id, center.tracks()[t].id);
      const auto& mine = peers[0].tracks()[t].filter;
      const auto& theirs = center.tracks()[t].filter;
      const double scale = 1.0 + theirs.mean.norm();
      worst_state_gap = std::max(worst_state_gap, (mine.mean - theirs.mean).norm() / scale);
    }

    std::vector<Vector3> present;
    for (const auto& truth : truths) {
      if (truth.present_at(k)) present.push_back(truth.at(k).head<3>());
    }
    std::vector<Vector3> confirmed;
    for (const auto& track : peers[0].tracks()) {
      if (track.status == TrackStatus::kConfirmed) {
        confirmed.push_back(track.filter.mean.head<3>());
      }
    }
    last = gospa(present, confirmed, {.cutoff_m = 100.0, .order = 2.0});
  }
  EXPECT_GT(compared_associations, 1000U);  // the comparison covered real association work
  EXPECT_GT(clutter_detections, 1000U);     // and real clutter
  EXPECT_LT(worst_state_gap, 1e-9);
  // After the last round: the four flights still in the air are tracked, nothing else.
  EXPECT_EQ(last.missed_targets, 0U);
  EXPECT_EQ(last.false_estimates, 0U);
  EXPECT_LT(std::sqrt(last.localisation / static_cast<double>(last.assigned)), 20.0);
}

}  // namespace
}  // namespace skyfuse
