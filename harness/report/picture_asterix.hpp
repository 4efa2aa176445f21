#pragma once
// `skyfuse run --asterix-record FILE` of a run of many aircraft: every node's picture after
// each round as CAT062 system tracks (docs/asterix.md), one UDP datagram per node and round in
// a pcap file, so that Wireshark and air-traffic tools read the run. Each node's tracks are
// numbered by its own TrackNumbers from its own pictures: nodes holding the same picture send
// the same bytes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/asterix/track_numbers.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/geodesy.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::harness {

/// Where a node's datagrams come from in the file: 127.0.(id / 256).(id % 256), ASTERIX's
/// usual port 8600 (the center, node 0, is 127.0.0.0); all go to 127.0.0.1:8600.
asterix::UdpEndpoint asterix_source_of(int node);

/// Track `track` of a node's picture numbered `number`, at `time_of_day_s`: the position in
/// the scenario's east-north-up plane (I062/100) and as WGS-84 through `anchor` (I062/105,
/// I062/130's height), the velocity, the accuracies from the covariance's position and
/// velocity blocks, the address where the track holds one. The data source is the network's
/// (SAC 0, SIC 1), whichever node sends it.
asterix::SystemTrack system_track(const wire::PictureTrack& track, std::uint16_t number,
                                  double time_of_day_s, const GeoAnchor& anchor);

class PictureAsterixRecording {
 public:
  PictureAsterixRecording(const std::filesystem::path& file, const PicturePlan& plan,
                          const std::vector<int>& nodes);

  /// Round k's pictures, one per node that sent one.
  void add(int k, const std::vector<wire::PictureRound>& rounds);
  /// Writes what is left; throws if the file could not be written.
  void close() { pcap_.close(); }

  /// Tracks left out because an item could not hold a value (beyond I062/185's ±8 192 m/s,
  /// say), and tracks without a number (more than 65 535 at once).
  std::size_t left_out() const { return left_out_; }

 private:
  const PicturePlan& plan_;
  asterix::PcapWriter pcap_;
  std::map<int, asterix::TrackNumbers> numbers_;  // per node
  std::size_t left_out_ = 0;
};

}  // namespace skyfuse::harness
