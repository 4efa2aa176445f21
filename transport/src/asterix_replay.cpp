#include "skyfuse/transport/asterix_replay.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "skyfuse/asterix/datagram.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

namespace skyfuse::transport {
namespace {

std::uint64_t round_of(double time_of_day_s, double time_step_s) {
  return static_cast<std::uint64_t>(std::llround(time_of_day_s / time_step_s));
}

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
    : station_id_(station_id) {
  if (!carried_by_asterix(sensor_kind)) {
    throw std::invalid_argument("--asterix-replay: station " + std::to_string(station_id) +
                                "'s sensor (" + std::string(sensor_kind) +
                                ") has no ASTERIX item that carries its detections");
  }
  if (station_id < 0 || station_id > 255) {
    throw std::invalid_argument("--asterix-replay: station " + std::to_string(station_id) +
                                " is past SIC's 255");
  }
  const FeedFile feed = read_feed(file);
  const asterix::DataSource mine{0, static_cast<std::uint8_t>(station_id)};
  const bool reports = sensor_kind == "position_velocity";
  std::map<std::uint64_t, std::vector<asterix::RadarPlot>> plots;
  std::map<std::uint64_t, std::vector<asterix::AdsbReport>> broadcasts;
  for (const asterix::Bytes& datagram : feed.datagrams) {
    const asterix::Decoded decoded = asterix::decode_datagram(datagram);
    for (std::size_t kind = 0; kind < refusals_.by_kind.size(); ++kind) {
      refusals_.by_kind[kind] += decoded.refusals.by_kind[kind];
    }
    if (reports) {
      for (const asterix::AdsbReport& r : decoded.reports) {
        if (r.source == mine) {
          broadcasts[round_of(r.time_of_applicability_s, time_step_s)].push_back(r);
        }
      }
    } else {
      for (const asterix::RadarPlot& p : decoded.plots) {
        if (p.source == mine) plots[round_of(p.time_of_day_s, time_step_s)].push_back(p);
      }
    }
  }
  const auto keep = [&](std::uint64_t k, std::optional<Scan> scan) {
    detections_ += scan->detections.size();
    scans_.emplace(k, std::move(*scan));
  };
  for (const auto& [k, round] : plots) {
    keep(k, scan_of_plots(station_id, sensor_kind, round, skipped_));
  }
  for (const auto& [k, round] : broadcasts) {
    keep(k, scan_of_reports(station_id, round, anchor, skipped_));
  }
}

Scan ReplayedScans::scan_at(std::uint64_t k, const DetectionNoise& noise) const {
  const auto at = scans_.find(k);
  Scan scan = at == scans_.end() ? Scan{station_id_, {}, {}, {}} : at->second;
  scan.noise = noise;
  return scan;
}

}  // namespace skyfuse::transport
