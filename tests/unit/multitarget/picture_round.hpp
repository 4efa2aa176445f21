#pragma once
// One round of a picture as the in-process tests drive it: every peer predicts, each station
// reports its own scan against its own peer's prediction, every peer fuses every report, and the
// center updates its prediction with every scan. Returns the reports, ascending station id.

#include <cstdint>
#include <span>
#include <vector>

#include "skyfuse/multitarget/associator.hpp"
#include "skyfuse/multitarget/scan.hpp"

namespace skyfuse::test {

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
