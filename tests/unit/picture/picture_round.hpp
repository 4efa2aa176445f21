#pragma once
// One round of a picture as the in-process tests drive it: every peer predicts, each station
// reports its own scan against its own peer's prediction, every peer fuses every report, and the
// center updates its prediction with every scan. Returns the reports, ascending station id.

#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "skyfuse/picture/associator.hpp"
#include "skyfuse/picture/picture_sensor.hpp"
#include "skyfuse/picture/scan.hpp"
#include "skyfuse/picture/track_table.hpp"
#include "skyfuse/registry/make_parts.hpp"

namespace skyfuse::test {

/// A station's sensor as it measures the truth's kinematics (what simulate_scan takes).
template <int N>
PictureSensor<kKinematicsDim> truth_sensor_of(const KnownStation<N>& station) {
  return std::visit(
      []<typename S>(const S& sensor) -> PictureSensor<kKinematicsDim> {
        if constexpr (std::is_constructible_v<TruthSensorOf<S>, const S&>) {
          return TruthSensorOf<S>(sensor);  // more than a site (multilateration's receivers)
        } else {
          return TruthSensorOf<S>(sensor.site());
        }
      },
      station.sensor);
}

/// Where a station's sensor stands (the origin for one that rides on the aircraft).
template <int N>
Vector3 site_of(const KnownStation<N>& station) {
  return std::visit([](const auto& sensor) -> Vector3 { return sensor.site(); }, station.sensor);
}

template <typename Peer, typename Center>
std::vector<typename Peer::Report> play_picture_round(
    std::uint64_t step, std::vector<Peer>& peers, Center& center,
    std::span<const typename Peer::Station> stations, std::span<const Scan> scans) {
  for (Peer& peer : peers) peer.predict();
  center.predict();
  std::vector<typename Peer::Report> reports;
  AssociationWork work;
  for (std::size_t s = 0; s < stations.size(); ++s) {
    reports.push_back(peers[s].report(stations[s], scans[s], work));
  }
  for (Peer& peer : peers) peer.fuse(step, reports);
  center.update(step, scans);
  return reports;
}

}  // namespace skyfuse::test
