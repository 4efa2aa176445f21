#include "skyfuse/transport/asterix_replay.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/asterix/pcap_stream.hpp"
#include "skyfuse/transport/scan_asterix.hpp"
#include "skyfuse/transport/scan_feed.hpp"

namespace skyfuse::transport {
namespace {

bool starts_like_pcap(std::istream& in) {
  std::array<std::uint8_t, 4> first{};
  in.read(reinterpret_cast<char*>(first.data()), first.size());
  const bool whole = in.gcount() == static_cast<std::streamsize>(first.size());
  in.clear();
  in.seekg(0);
  if (!whole) return false;
  const std::uint32_t magic = static_cast<std::uint32_t>(first[0]) << 24U |
                              static_cast<std::uint32_t>(first[1]) << 16U |
                              static_cast<std::uint32_t>(first[2]) << 8U | first[3];
  return magic == 0xA1B2C3D4U || magic == 0xD4C3B2A1U || magic == 0xA1B23C4DU ||
         magic == 0x4D3CB2A1U || magic == 0x0A0D0D0AU;
}

// Hands each datagram of a feed file to `take`, one at a time: a pcap's (classic or its
// nanosecond form; pcapng is refused by the reader, naming it), read as it goes, or a file of
// raw ASTERIX data blocks one after another, read as one. Returns the pcap frames skipped.
template <typename Take>
std::uint64_t for_each_datagram(const std::filesystem::path& file, Take take) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("--asterix-replay: cannot read " + file.string());
  if (!starts_like_pcap(in)) {
    const asterix::Bytes bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    if (!bytes.empty()) take(bytes);
    return 0;
  }
  asterix::PcapStream stream(in);
  while (const auto d = stream.next()) take(d->payload);
  if (stream.error()) {
    throw std::runtime_error("--asterix-replay: " + file.string() + ": " + *stream.error());
  }
  return stream.skipped().total();
}

}  // namespace

AsterixFeedCounts count_asterix_feed(const std::filesystem::path& file) {
  AsterixFeedCounts counts;
  asterix::Decoded decoded;
  counts.frames_skipped = for_each_datagram(file, [&](const asterix::Bytes& datagram) {
    ++counts.datagrams;
    asterix::decode_datagram(datagram, decoded);
    counts.plots += decoded.plots.size();
    counts.reports += decoded.reports.size();
    counts.system_tracks += decoded.tracks.size();
    decoded.plots.clear();
    decoded.reports.clear();
    decoded.tracks.clear();
  });
  counts.refused = decoded.refusals;
  return counts;
}

ReplayedScans::ReplayedScans(const std::filesystem::path& file, const Scenario& scenario,
                             const StationConfig& station)
    : file_(file), station_id_(station.id) {
  ScanFeed feed("--asterix-replay", scenario, station);
  for_each_datagram(file, [&](const asterix::Bytes& datagram) { feed.take(datagram); });
  for (const std::uint64_t k : feed.rounds()) scans_.emplace(k, feed.take_scan(k, {}));
  detections_ = feed.detections();
  refusals_ = feed.refusals();
  skipped_ = feed.skipped();
}

Scan ReplayedScans::scan_at(std::uint64_t k, const DetectionNoise& noise) {
  const auto at = scans_.find(k);
  Scan scan = at == scans_.end() ? Scan{station_id_, {}, {}, {}} : at->second;
  scan.noise = noise;
  return scan;
}

std::string ReplayedScans::summary() const {
  return fmt::format("station {} takes its scans from {}: {} rounds, {} detections, {} skipped",
                     station_id_, file_.string(), rounds(), detections(), skipped());
}

}  // namespace skyfuse::transport
