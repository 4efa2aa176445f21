#include "report/picture_asterix.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::harness {
namespace {

// The file's clock: 2026-01-01T00:00:00Z plus the run's own time, so that a run's file is the
// same bytes whenever it is made and its times of track are seconds since that midnight.
constexpr std::int64_t kEpochNs = 1'767'225'600'000'000'000;
constexpr double kSecondsPerDay = 86'400.0;
// One block per datagram, each within an unfragmented IPv4 UDP payload.
constexpr std::size_t kMaxDatagramOctets = 65'507;
// SAC 0 (no area assigned), SIC 1, until a scenario names its own.
constexpr asterix::DataSource kSystemSource{0, 1};

}  // namespace

asterix::UdpEndpoint asterix_source_of(int node) {
  const auto id = static_cast<std::uint32_t>(node);
  return {
      {127, 0, static_cast<std::uint8_t>((id >> 8) & 0xFF), static_cast<std::uint8_t>(id & 0xFF)},
      8600};
}

asterix::SystemTrack system_track(const wire::PictureTrack& track, std::uint16_t number,
                                  double time_of_day_s, const GeoAnchor& anchor) {
  asterix::SystemTrack out;
  // The network is one system (SDPS), whichever node sends its picture: one data source, so
  // that nodes holding one picture send the same bytes (the datagram's source names the node).
  out.source = kSystemSource;
  out.service_id = 1;
  out.track_number = number;
  out.time_of_track_s = time_of_day_s;
  out.status.tentative = !track.confirmed();
  const auto& x = track.x();
  const Vector3 enu(x[0], x[1], x[2]);
  out.x_m = enu.x();
  out.y_m = enu.y();
  const Vector3 geodetic = from_local_enu(anchor, enu);
  out.latitude_deg = geodetic.x();
  out.longitude_deg = geodetic.y();
  out.geometric_altitude_m = geodetic.z();
  out.vx_mps = x[3];
  out.vy_mps = x[4];
  const int n = static_cast<int>(x.size());
  if (const auto p = transport::unpack_upper<Eigen::Dynamic>(track.covariance(), n)) {
    const Eigen::MatrixXd& c = *p;
    out.accuracy =
        asterix::TrackAccuracy{std::sqrt(c(0, 0)), std::sqrt(c(1, 1)), c(0, 1),
                               std::sqrt(c(3, 3)), std::sqrt(c(4, 4)), std::sqrt(c(2, 2))};
  }
  if (track.address() != 0) out.address = track.address();
  return out;
}

PictureAsterixRecording::PictureAsterixRecording(const std::filesystem::path& file,
                                                 const PicturePlan& plan,
                                                 const std::vector<int>& nodes)
    : plan_(plan), pcap_(file) {
  for (const int node : nodes) numbers_.emplace(node, asterix::TrackNumbers());
}

void PictureAsterixRecording::add(int k, const std::vector<wire::PictureRound>& rounds) {
  const double time_s = k * plan_.scenario.time_step_s;
  const double time_of_day_s = std::fmod(time_s, kSecondsPerDay);
  const auto time_ns = kEpochNs + static_cast<std::int64_t>(std::llround(time_s * 1e9));
  for (const wire::PictureRound& round : rounds) {
    const auto numbers = numbers_.find(round.source_id());
    if (numbers == numbers_.end()) continue;
    std::vector<std::uint64_t> ids;
    for (const wire::PictureTrack& t : round.tracks()) ids.push_back(t.track_id());
    numbers->second.update(ids, static_cast<std::uint64_t>(k));
    left_out_ += numbers->second.unnumbered();
    // Each track encoded once; one it cannot hold is left out, not its whole block.
    std::vector<asterix::Bytes> records;
    for (const wire::PictureTrack& t : round.tracks()) {
      if (t.x().size() < 6) continue;
      const auto number = numbers->second.number_of(t.track_id());
      if (!number) continue;
      asterix::Encoded record = asterix::encode_cat062_record(
          system_track(t, *number, time_of_day_s, plan_.scenario.anchor));
      if (!record) {
        ++left_out_;
        continue;
      }
      records.push_back(std::move(record.bytes));
    }
    // A picture without tracks sends nothing that round; a large one, several datagrams.
    std::optional<asterix::EncodeError> error;
    std::vector<asterix::Bytes> blocks =
        asterix::encode_blocks(asterix::kCat062, records, kMaxDatagramOctets, error);
    // Only a record longer than a datagram fails here, and a track's is under a hundred octets.
    if (error) throw std::logic_error("--asterix-record: a CAT062 record longer than a datagram");
    for (asterix::Bytes& block : blocks) {
      pcap_.write({time_ns,
                   asterix_source_of(round.source_id()),
                   {{127, 0, 0, 1}, 8600},
                   std::move(block)});
    }
  }
}

}  // namespace skyfuse::harness
