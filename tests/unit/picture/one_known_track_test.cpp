// One aircraft known from the start, always detected, no clutter: the picture of one track
// computes the single-target peers' bits. The network's one-aircraft runs are the picture's
// special case in arithmetic; this holds them to it while both still exist
// (docs/picture.md, "Not yet").

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "skyfuse/models/constant_acceleration.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/registry/make_parts.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/scenario/scenario_loader.hpp"
#include "skyfuse/sim/monte_carlo.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/tracking/unscented_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"

namespace skyfuse {
namespace {

using Model = ConstantAcceleration3D;
using Sensor = RangeAzimuthElevation<Model::kDim>;

// Runs paper 000's scenario with filter part `filter_kind`, whose increment rule is `Rule`,
// both ways and compares every step's fused estimate bit for bit.
template <typename Rule>
void expect_the_single_target_bits(const std::string& filter_kind) {
  using Tracks = PeerModelTracks<Model, Rule>;
  using Picture = PeerPicture<Tracks>;
  constexpr int kStations = 4;
  constexpr std::uint64_t kRun = 3;
  Scenario scenario = load_default_scenario();
  scenario.steps = 400;
  scenario.filter.kind = filter_kind;
  const double speed = scenario.target.speeds_mps.front();
  const TruthTrajectory truth =
      generate_truth(scenario.target, speed, scenario.time_step_s, scenario.steps);

  // The single-target network's fused estimate at every step, before its predict.
  std::vector<GaussianState<Model::kDim>> single;
  simulate_run(scenario, truth, kStations, kRun, [&](const StepRecord& r) {
    GaussianState<Model::kDim> estimate;
    estimate.mean = r.decentralised.mean;
    estimate.covariance = r.decentralised.covariance;
    single.push_back(estimate);
  });
  ASSERT_EQ(single.size(), static_cast<std::size_t>(scenario.steps));

  // The picture: the same stations, one track known from the start, nothing to start or end.
  std::vector<KnownStation<Model::kDim>> stations;
  for (int s = 0; s < kStations; ++s) {
    const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
    stations.push_back({station.id,
                        PictureSensor<Model::kDim>(make_sensor<Sensor>(station)),
                        DetectionNoise(station_noise_covariance<3>(scenario, station, kRun)),
                        station.weight,
                        {}});
  }
  TrackerConfig config;
  config.association.gate_probability = 1.0 - 1e-15;  // the single-target run has no gate
  config.initiation.min_stations = kStations + 1;
  config.management.max_position_std_m = 1e9;
  Picture picture(
      Tracks(make_motion_model<Model>(scenario), scenario.filter.initial_covariance_diag), stations,
      config);
  picture.add_known_track(make_track_id(0, 0, 0),
                          initial_estimate<Model>(scenario, truth.states.front(), kRun));
  const std::vector<TargetTruth> aircraft = {TargetTruth{"T0", 0, truth.states}};

  AssociationWork work;
  std::size_t identical = 0;
  for (int k = 0; k < scenario.steps; ++k) {
    if (k > 0) picture.predict();
    std::vector<typename Picture::Report> reports;
    for (int s = 0; s < kStations; ++s) {
      const StationConfig& station = scenario.stations[static_cast<std::size_t>(s)];
      const Scan scan = simulate_scan(station.id, make_sensor<TruthSensorOf<Sensor>>(station),
                                      station.position_m, fixed_noise<3>(stations[s].noise),
                                      DetectionConfig{}, aircraft, k, scenario.seed, kRun);
      reports.push_back(picture.report(stations[s], scan, work));
      ASSERT_EQ(reports.back().updates.size(), 1U) << "step " << k;
    }
    picture.fuse(static_cast<std::uint64_t>(k), reports);
    ASSERT_EQ(picture.tracks().size(), 1U) << "step " << k;
    const GaussianState<Model::kDim>& mine = picture.tracks().front().filter;
    EXPECT_TRUE(mine.mean == single[static_cast<std::size_t>(k)].mean) << "step " << k;
    EXPECT_TRUE(mine.covariance == single[static_cast<std::size_t>(k)].covariance) << "step " << k;
    if (mine.mean == single[static_cast<std::size_t>(k)].mean) ++identical;
  }
  EXPECT_EQ(identical, static_cast<std::size_t>(scenario.steps));
}

TEST(OneKnownTrack, ThePictureComputesTheSingleTargetEkfPeersBits) {
  expect_the_single_target_bits<EkfIncrementRule>("ekf");
}

TEST(OneKnownTrack, ThePictureComputesTheSingleTargetUnscentedPeersBits) {
  expect_the_single_target_bits<UnscentedIncrementRule>("ukf");
}

}  // namespace
}  // namespace skyfuse
