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

// Whether the file `in` reads starts like a pcap (asterix::starts_like_pcap); `in` is back at
// its start afterwards.
bool starts_like_pcap(std::istream& in) {
  std::array<std::uint8_t, 4> first{};
  in.read(reinterpret_cast<char*>(first.data()), first.size());
  const auto read = static_cast<std::size_t>(in.gcount());
  in.clear();
  in.seekg(0);
  return asterix::starts_like_pcap(std::span(first.data(), read));
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
