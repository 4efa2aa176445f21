#include "skyfuse/transport/picture_cat062.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "skyfuse/asterix/data_block.hpp"
#include "skyfuse/picture/identification.hpp"
#include "skyfuse/transport/wire_conversion.hpp"

namespace skyfuse::transport {
namespace {

constexpr double kSecondsPerDay = 86'400.0;

}  // namespace

asterix::DataSource system_source(const Scenario& scenario) {
  return {static_cast<std::uint8_t>(scenario.asterix.sac),
          static_cast<std::uint8_t>(scenario.asterix.sic)};
}

asterix::SystemTrack system_track(const wire::PictureTrack& track, std::uint16_t number,
                                  asterix::DataSource source, double time_of_day_s,
                                  const GeoAnchor& anchor) {
  asterix::SystemTrack out;
  out.source = source;
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
  if (const auto p = unpack_upper<Eigen::Dynamic>(track.covariance(), n)) {
    const Eigen::MatrixXd& c = *p;
    out.accuracy =
        asterix::TrackAccuracy{std::sqrt(c(0, 0)), std::sqrt(c(1, 1)), c(0, 1),
                               std::sqrt(c(3, 3)), std::sqrt(c(4, 4)), std::sqrt(c(2, 2))};
  }
  if (track.address() != 0) out.address = track.address();
  // A node sends only callsigns it checked (picture_callsigns.hpp); another is left out.
  if (track.identification() != kNoIdentification && valid_identification(track.identification())) {
    out.callsign = callsign_of(track.identification());
  }
  return out;
}

double time_of_day_s(std::uint64_t k, double time_step_s) {
  return std::fmod(static_cast<double>(k) * time_step_s, kSecondsPerDay);
}

std::vector<asterix::Bytes> PictureCat062::blocks(std::uint64_t k,
                                                  const wire::PictureRound& round) {
  const double time_s = time_of_day_s(k, time_step_s_);
  // Each track encoded once; one it cannot hold is left out, not its whole block.
  std::vector<asterix::Bytes> records;
  for (const wire::PictureTrack& t : round.tracks()) {
    if (t.x().size() < 6) continue;
    if (t.number() == 0) {
      ++left_out_;  // more tracks than numbers
      continue;
    }
    asterix::Encoded record =
        asterix::encode_cat062_record(system_track(t, t.number(), source_, time_s, anchor_));
    if (!record) {
      ++left_out_;
      continue;
    }
    records.push_back(std::move(record.bytes));
  }
  // A picture without tracks sends nothing that round; a large one, several datagrams.
  std::optional<asterix::EncodeError> error;
  std::vector<asterix::Bytes> blocks =
      asterix::encode_blocks(asterix::kCat062, records, asterix::kMaxUdpPayload, error);
  // Only a record longer than a datagram fails here, and a track's is under a hundred octets.
  if (error) throw std::logic_error("CAT062: a record longer than a datagram");
  return blocks;
}

std::string asterix_out_summary(const PictureAsterixOut& out) {
  const asterix::UdpEndpoint& to = out.sender().destination();
  return fmt::format(
      "--asterix-out {}.{}.{}.{}:{}: {} CAT062 datagrams sent, {} refused by the system, "
      "{} tracks left out",
      to.address[0], to.address[1], to.address[2], to.address[3], to.port, out.sender().sent(),
      out.sender().failed(), out.left_out());
}

std::unique_ptr<PictureAsterixOut> make_asterix_out(const std::string& destination,
                                                    const Scenario& scenario) {
  if (destination.empty()) return nullptr;
  std::string error;
  const auto endpoint = asterix::parse_udp_endpoint(destination, error);
  if (!endpoint) throw std::invalid_argument("--asterix-out: " + error);
  return std::make_unique<PictureAsterixOut>(*endpoint, scenario);
}

}  // namespace skyfuse::transport
