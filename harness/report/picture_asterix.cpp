#include "report/picture_asterix.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/sim/picture_detections.hpp"
#include "skyfuse/transport/scan_asterix.hpp"

namespace skyfuse::harness {
namespace {

// The file's clock: 2026-01-01T00:00:00Z plus the run's own time, so that a run's file is the
// same bytes whenever it is made and its times of track are seconds since that midnight.
constexpr std::int64_t kEpochNs = 1'767'225'600'000'000'000;
// A station's sensor feed comes from its own address on this port, its picture on 8600.
constexpr std::uint16_t kSensorPort = 8601;

}  // namespace

asterix::UdpEndpoint asterix_source_of(int node) {
  const auto id = static_cast<std::uint32_t>(node);
  return {
      {127, 0, static_cast<std::uint8_t>((id >> 8) & 0xFF), static_cast<std::uint8_t>(id & 0xFF)},
      8600};
}

PictureAsterixRecording::PictureAsterixRecording(const std::filesystem::path& file,
                                                 const PicturePlan& plan,
                                                 const std::vector<int>& nodes,
                                                 const std::vector<TargetTruth>& truth)
    : plan_(plan), truth_(truth), pcap_(file) {
  for (const int node : nodes) {
    nodes_.emplace(node, transport::PictureCat062(plan.scenario));
  }
}

std::size_t PictureAsterixRecording::left_out() const {
  std::size_t left = 0;
  for (const auto& [node, cat062] : nodes_) left += cat062.left_out();
  return left;
}

void PictureAsterixRecording::add(int k, const std::vector<wire::PictureRound>& rounds) {
  const double time_s = k * plan_.scenario.time_step_s;
  const auto time_ns = kEpochNs + static_cast<std::int64_t>(std::llround(time_s * 1e9));
  add_scans(k, time_ns);
  for (const wire::PictureRound& round : rounds) {
    const auto node = nodes_.find(round.source_id());
    if (node == nodes_.end()) continue;
    for (asterix::Bytes& block : node->second.blocks(static_cast<std::uint64_t>(k), round)) {
      pcap_.write({time_ns,
                   asterix_source_of(round.source_id()),
                   {{127, 0, 0, 1}, 8600},
                   std::move(block)});
    }
  }
}

void PictureAsterixRecording::add_scans(int k, std::int64_t time_ns) {
  const double time_of_day_s =
      transport::time_of_day_s(static_cast<std::uint64_t>(k), plan_.scenario.time_step_s);
  const std::vector<SimulatedScan> scans =
      simulated_scans_at(plan_.scenario, truth_, plan_.stations, plan_.mc_run, k);
  for (std::size_t s = 0; s < scans.size(); ++s) {
    const StationConfig& station = plan_.scenario.stations[s];
    transport::ScanRecords records =
        transport::scan_records(scans[s], station, time_of_day_s, plan_.scenario);
    detections_left_out_ += records.left_out;
    if (records.category == 0) {
      detections_left_out_ += scans[s].scan.detections.size();
      continue;
    }
    std::optional<asterix::EncodeError> error;
    std::vector<asterix::Bytes> blocks =
        asterix::encode_blocks(records.category, records.records, asterix::kMaxUdpPayload, error);
    if (error) throw std::logic_error("--asterix-record: a plot's record longer than a datagram");
    asterix::UdpEndpoint from = asterix_source_of(station.id);
    from.port = kSensorPort;
    for (asterix::Bytes& block : blocks) {
      pcap_.write({time_ns, from, {{127, 0, 0, 1}, 8600}, std::move(block)});
    }
  }
}

}  // namespace skyfuse::harness
