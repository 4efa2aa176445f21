#pragma once
// `skyfuse run --asterix-record FILE` of a run of many aircraft: every node's picture after
// each round as CAT062 system tracks (docs/asterix.md), one UDP datagram per node and round in
// a pcap file, and every station's scan as CAT048 plots or CAT021 reports
// (transport/scan_asterix.hpp), so that Wireshark and air-traffic tools read the run. Each node's
// picture is encoded as its own `--asterix-out` sends it (transport/picture_cat062.hpp): nodes
// holding the same picture send the same bytes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/sim/picture_plan.hpp"
#include "skyfuse/traffic/target_truth.hpp"
#include "skyfuse/transport/picture_cat062.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::harness {

/// Where a node's datagrams come from in the file: 127.0.(id / 256).(id % 256), ASTERIX's
/// usual port 8600 (the center, node 0, is 127.0.0.0); all go to 127.0.0.1:8600.
asterix::UdpEndpoint asterix_source_of(int node);

class PictureAsterixRecording {
 public:
  /// `truth`: the run's aircraft, whose scans it simulates again as the stations do
  /// (sim/picture_detections.hpp); it must outlive the recording.
  PictureAsterixRecording(const std::filesystem::path& file, const PicturePlan& plan,
                          const std::vector<int>& nodes, const std::vector<TargetTruth>& truth);

  /// Round k: the stations' scans (scan_asterix.hpp) from 127.0.(id / 256).(id % 256):8601,
  /// then the pictures, one per node that sent one, from the node's address on port 8600.
  void add(int k, const std::vector<wire::PictureRound>& rounds);
  /// Writes what is left; throws if the file could not be written.
  void close() { pcap_.close(); }

  /// Tracks left out because an item could not hold a value (beyond I062/185's ±8 192 m/s,
  /// say), and tracks without a number (more than 65 535 at once).
  std::size_t left_out() const;
  /// Detections of a scan left out: a value outside its item's range, or a sensor no item
  /// carries (a 3-D radar's elevation, multilateration's time differences).
  std::size_t detections_left_out() const { return detections_left_out_; }

 private:
  void add_scans(int k, std::int64_t time_ns);

  const PicturePlan& plan_;
  const std::vector<TargetTruth>& truth_;
  asterix::PcapWriter pcap_;
  std::map<int, transport::PictureCat062> nodes_;
  std::size_t detections_left_out_ = 0;
};

}  // namespace skyfuse::harness
