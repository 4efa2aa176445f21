#pragma once
// The picture benchmarks' traffic: N aircraft flying straight over a square, radars on a
// circle around it, and a picture that tracks them all (picture_bench.cpp,
// picture_wire_bench.cpp).

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>
#include <variant>
#include <vector>

#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"

namespace skyfuse::bench {

using Model = ConstantVelocity3D;
using TrackSensor = RangeAzimuthElevation<Model::kDim>;
using TruthSensor = RangeAzimuthElevation<kKinematicsDim>;
using PeerTracks = PeerModelTracks<Model, EkfIncrementRule>;
using Peer = PeerPicture<PeerTracks>;
using Station = KnownStation<Model::kDim>;

constexpr int kWarmUpSteps = 8;  // rounds for every aircraft to get a confirmed track

// N aircraft flying straight and level over a square of about one aircraft per km^2.
inline std::vector<TargetTruth> traffic(int aircraft, int steps) {
  std::mt19937_64 rng(1);
  const double half_side = 500.0 * std::sqrt(static_cast<double>(aircraft));
  std::uniform_real_distribution<double> across(-half_side, half_side);
  std::uniform_real_distribution<double> height(100.0, 600.0);
  std::uniform_real_distribution<double> speed(20.0, 60.0);
  std::uniform_real_distribution<double> heading(-std::numbers::pi, std::numbers::pi);
  std::vector<TargetTruth> truths;
  for (int a = 0; a < aircraft; ++a) {
    // One draw at a time, the height first (a call's arguments have no fixed order in C++).
    const double up = height(rng);
    const double north = across(rng);
    const Vector3 start(across(rng), north, up);
    const double h = heading(rng);
    const Vector3 velocity = speed(rng) * Vector3(std::cos(h), std::sin(h), 0.0);
    TargetTruth truth{fmt::format("T{}", a), 0, {}};
    for (int k = 0; k < steps; ++k) {
      Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
      x.head<3>() = start + k * velocity;
      x.segment<3>(3) = velocity;
      truth.states.push_back(x);
    }
    truths.push_back(std::move(truth));
  }
  return truths;
}

// `count` radars on a circle around the area, seeing all of it.
inline std::vector<Station> radars(int aircraft, int count) {
  const double radius = 700.0 * std::sqrt(static_cast<double>(aircraft)) + 2000.0;
  Covariance<3> noise = Covariance<3>::Zero();
  const double angle_std = 0.05 * std::numbers::pi / 180.0;
  noise.diagonal() << 5.0 * 5.0, angle_std * angle_std, angle_std * angle_std;
  std::vector<Station> stations;
  for (int i = 0; i < count; ++i) {
    const double bearing = 2.0 * std::numbers::pi * i / count;
    const Vector3 site(radius * std::cos(bearing), radius * std::sin(bearing), 30.0);
    stations.push_back({i + 1, TrackSensor(site), noise, 1.0, {}});
  }
  return stations;
}

// P_D 0.9 and 10 false alarms a scan (or what is given), every aircraft in view.
inline DetectionConfig detection_for(int aircraft, double probability = 0.9,
                                     double clutter_per_scan = 10.0) {
  DetectionConfig detection;
  detection.probability = probability;
  detection.field_of_view.max_range_m = 4.0 * (700.0 * std::sqrt(aircraft) + 2000.0);
  detection.field_of_view.min_elevation_rad = 0.0;
  detection.clutter_per_scan = clutter_per_scan;
  return detection;
}

// Every station's scan of step `step`.
inline std::vector<Scan> scans_of(const std::vector<Station>& stations,
                                  const DetectionConfig& detection,
                                  const std::vector<TargetTruth>& truths, int step) {
  std::vector<Scan> scans;
  for (const auto& s : stations) {
    const Vector3 site = std::get<TrackSensor>(s.sensor).site();
    scans.push_back(simulate_scan(s.id, TruthSensor(site), site, fixed_noise<3>(s.noise), detection,
                                  truths, step, 7, 0));
  }
  return scans;
}

// A picture of the traffic after kWarmUpSteps rounds, every aircraft tracked.
inline Peer warmed_picture(const std::vector<Station>& stations, const DetectionConfig& detection,
                           const std::vector<TargetTruth>& truths,
                           const TrackerConfig& tracker = {}) {
  Peer peer(PeerTracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0)), stations,
            tracker);
  AssociationWork work;
  std::vector<Peer::Report> reports(stations.size());
  for (int k = 0; k < kWarmUpSteps; ++k) {
    const auto scans = scans_of(stations, detection, truths, k);
    peer.predict();
    for (std::size_t s = 0; s < stations.size(); ++s) {
      reports[s] = peer.report(stations[s], scans[s], work);
    }
    peer.fuse(static_cast<std::uint64_t>(k), reports);
  }
  return peer;
}

}  // namespace skyfuse::bench
