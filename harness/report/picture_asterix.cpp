#include "report/picture_asterix.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::harness {
namespace {

// The file's clock: 2026-01-01T00:00:00Z plus the run's own time, so that a run's file is the
// same bytes whenever it is made and its times of track are seconds since that midnight.
constexpr std::int64_t kEpochNs = 1'767'225'600'000'000'000;
constexpr double kSecondsPerDay = 86'400.0;
// A block's LEN is 16 bits: a picture of more tracks goes in several blocks, one datagram each.
constexpr std::size_t kTracksPerBlock = 500;
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
    std::vector<asterix::SystemTrack> tracks;
    for (const wire::PictureTrack& t : round.tracks()) {
      if (t.x().size() < 6) continue;
      const auto number = numbers->second.number_of(t.track_id());
      if (!number) continue;
      asterix::SystemTrack track = system_track(t, *number, time_of_day_s, plan_.scenario.anchor);
      if (!asterix::encode_cat062_record(track)) {
        ++left_out_;
        continue;
      }
      tracks.push_back(std::move(track));
    }
    // A picture without tracks sends nothing that round.
    for (std::size_t first = 0; first < tracks.size(); first += kTracksPerBlock) {
      const std::size_t count = std::min(kTracksPerBlock, tracks.size() - first);
      const asterix::Encoded block = asterix::encode_cat062(
          std::span<const asterix::SystemTrack>(tracks).subspan(first, count));
      if (!block) continue;
      pcap_.write(
          {time_ns, asterix_source_of(round.source_id()), {{127, 0, 0, 1}, 8600}, block.bytes});
    }
  }
}

}  // namespace skyfuse::harness
