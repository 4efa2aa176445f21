#include "skyfuse/transport/asterix_replay.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/transport/scan_asterix.hpp"
#include "skyfuse/transport/scan_feed.hpp"

namespace skyfuse::transport {
namespace {

// A feed file's datagrams: a pcap's (classic or its nanosecond form; pcapng is refused by the
// reader, naming it), or a file of raw ASTERIX data blocks one after another, read as one.
struct FeedFile {
  std::vector<asterix::Bytes> datagrams;
  std::uint64_t frames_skipped = 0;
};

bool starts_like_pcap(const asterix::Bytes& bytes) {
  if (bytes.size() < 4) return false;
  const std::uint32_t magic = static_cast<std::uint32_t>(bytes[0]) << 24U |
                              static_cast<std::uint32_t>(bytes[1]) << 16U |
                              static_cast<std::uint32_t>(bytes[2]) << 8U | bytes[3];
  return magic == 0xA1B2C3D4U || magic == 0xD4C3B2A1U || magic == 0xA1B23C4DU ||
         magic == 0x4D3CB2A1U || magic == 0x0A0D0D0AU;
}

FeedFile read_feed(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("--asterix-replay: cannot read " + file.string());
  asterix::Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  FeedFile feed;
  if (!starts_like_pcap(bytes)) {
    if (!bytes.empty()) feed.datagrams.push_back(std::move(bytes));
    return feed;
  }
  asterix::PcapContents contents = asterix::read_pcap(bytes);
  if (contents.error) {
    throw std::runtime_error("--asterix-replay: " + file.string() + ": " + *contents.error);
  }
  feed.frames_skipped = contents.skipped.total();
  for (asterix::UdpDatagram& d : contents.datagrams) feed.datagrams.push_back(std::move(d.payload));
  return feed;
}

}  // namespace

AsterixFeedCounts count_asterix_feed(const std::filesystem::path& file) {
  const FeedFile feed = read_feed(file);
  AsterixFeedCounts counts;
  counts.frames_skipped = feed.frames_skipped;
  asterix::Decoded decoded;
  for (const asterix::Bytes& datagram : feed.datagrams) {
    ++counts.datagrams;
    asterix::decode_datagram(datagram, decoded);
    counts.plots += decoded.plots.size();
    counts.reports += decoded.reports.size();
    counts.system_tracks += decoded.tracks.size();
    decoded.plots.clear();
    decoded.reports.clear();
    decoded.tracks.clear();
  }
  counts.refused = decoded.refusals;
  return counts;
}

ReplayedScans::ReplayedScans(const std::filesystem::path& file, int station_id,
                             std::string_view sensor_kind, const GeoAnchor& anchor,
                             double time_step_s)
    : file_(file), station_id_(station_id) {
  ScanFeed feed("--asterix-replay", station_id, sensor_kind, anchor, time_step_s);
  for (const asterix::Bytes& datagram : read_feed(file).datagrams) feed.take(datagram);
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
