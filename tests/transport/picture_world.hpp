#pragma once
// A small world of many aircraft for the picture's wire and exchange tests: five aircraft flying
// east in parallel lanes, three radars around them, misses and clutter.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include "skyfuse/models/constant_velocity.hpp"
#include "skyfuse/models/range_azimuth_elevation.hpp"
#include "skyfuse/picture/peer_picture.hpp"
#include "skyfuse/picture/track_filters.hpp"
#include "skyfuse/scenario/measurement_simulation.hpp"
#include "skyfuse/tracking/ekf_increment_rule.hpp"
#include "skyfuse/traffic/scan_simulation.hpp"
#include "skyfuse/transport/picture_round_scans.hpp"
#include "skyfuse/transport/picture_wire.hpp"

namespace skyfuse::test {

struct PictureWorld {
  using Model = ConstantVelocity3D;
  using Sensor = RangeAzimuthElevation<Model::kDim>;
  using Tracks = PeerModelTracks<Model, EkfIncrementRule>;
  using Peer = PeerPicture<Tracks>;
  using Station = KnownStation<Model::kDim>;

  explicit PictureWorld(int rounds) {
    for (int a = 0; a < 5; ++a) {
      TargetTruth truth{"aircraft", 0, {}};
      for (int k = 0; k < rounds; ++k) {
        Vector<kKinematicsDim> x = Vector<kKinematicsDim>::Zero();
        x.head<3>() = Vector3(-2000.0 + 30.0 * k, 800.0 * a - 1600.0, 300.0 + 50.0 * a);
        x.segment<3>(3) = Vector3(30.0, 0.0, 0.0);
        truth.states.push_back(x);
      }
      truths.push_back(std::move(truth));
    }
    Covariance<3> noise = Covariance<3>::Zero();
    noise.diagonal() << 25.0, 1e-6, 1e-6;
    for (int i = 0; i < 3; ++i) {
      const Vector3 site(6000.0 * std::cos(2.0 * i), 6000.0 * std::sin(2.0 * i), 30.0);
      stations.push_back({i + 1, Sensor(site), noise, 1.0, {}});
    }
    detection.probability = 0.9;
    detection.field_of_view.max_range_m = 20000.0;
    detection.clutter_per_scan = 2.0;
  }

  // The world's track filter.
  static Tracks track_filters() {
    return Tracks(Model(1.0, {0.5, 1.0}), Vector<Model::kDim>::Constant(100.0));
  }

  // The world's stations as the exchanges screen their samples.
  transport::RoundStations round_stations() const {
    return transport::RoundStations::of(std::span<const Station>(stations));
  }

  // An empty picture of the world's filter, at every peer the same.
  Peer empty_picture(const TrackerConfig& config = {}) const {
    return Peer(track_filters(), stations, config);
  }

  // Station `s`'s scan of round k (seeded: the same at every call).
  Scan scan(std::size_t s, int k) const {
    const auto& station = stations[s];
    const Vector3 site = std::get<Sensor>(station.sensor).site();
    return simulate_scan(station.id, RangeAzimuthElevation<kKinematicsDim>(site), site,
                         fixed_noise<3>(station.noise), detection, truths, k, 11, 0);
  }

  // Round k of one peer that reports and fuses every station's scan itself.
  void play_round(Peer& peer, int k, AssociationWork& work) const {
    peer.predict();
    std::vector<Peer::Report> reports;
    for (std::size_t s = 0; s < stations.size(); ++s) {
      reports.push_back(peer.report(stations[s], scan(s, k), work));
    }
    peer.fuse(static_cast<std::uint64_t>(k), reports);
  }

  // Round k of run `run_id`'s start at every node of `nodes` (each with a `picture` and an
  // `exchange`): it predicts its picture, scans and publishes its report against it.
  // `reference`, an in-process peer, predicts too; each station's own report against it is
  // returned.
  template <typename Nodes>
  std::vector<Peer::Report> publish_round(Nodes& nodes, Peer& reference, int k,
                                          AssociationWork& work, std::uint64_t run_id) const {
    reference.predict();
    std::vector<Peer::Report> own_reports;
    for (std::size_t s = 0; s < nodes.size(); ++s) {
      auto& n = nodes[s];
      n.picture.predict();
      const Scan station_scan = scan(s, k);
      own_reports.push_back(reference.report(stations[s], station_scan, work));
      n.exchange->publish(transport::to_wire<Model::kDim>(
          stations[s].sensor, station_scan, n.picture.report(stations[s], station_scan, work),
          run_id, static_cast<std::uint32_t>(k), n.picture.digest()));
    }
    return own_reports;
  }

  std::vector<TargetTruth> truths;
  std::vector<Station> stations;
  DetectionConfig detection;
};

}  // namespace skyfuse::test
