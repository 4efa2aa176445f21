#pragma once
/// \file
/// A node's picture as ASTERIX CAT062 system tracks (docs/asterix.md), round by round: what
/// `--asterix-out HOST:PORT` sends over UDP from a station or the center and what
/// `skyfuse run --asterix-record` writes into a pcap — the same bytes from the same picture, each
/// track under the number its node gave it (wire::PictureTrack::number,
/// transport/picture_numbers.hpp).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skyfuse/asterix/cat062.hpp"
#include "skyfuse/asterix/udp.hpp"
#include "skyfuse/traffic/geodesy.hpp"
#include "skyfuse/wire/skyfuse_picture.h"

namespace skyfuse::transport {

/// The network is one system (SDPS), whichever node sends its picture: one data source, the
/// scenario's `asterix` (SAC 0, no area assigned, and SIC 1 unless it says), so that nodes
/// holding one picture send the same bytes.
asterix::DataSource system_source(const Scenario& scenario);

/// Track `track` of a node's picture numbered `number`, from `source`, at `time_of_day_s`: the
/// position in
/// the scenario's east-north-up plane (I062/100) and as WGS-84 through `anchor` (I062/105,
/// I062/130's height), the velocity, the accuracies from the covariance's position and
/// velocity blocks, the address where the track holds one, and the callsign the node learnt for
/// that address (I062/245; picture_callsigns.hpp).
asterix::SystemTrack system_track(const wire::PictureTrack& track, std::uint16_t number,
                                  asterix::DataSource source, double time_of_day_s,
                                  const GeoAnchor& anchor);

/// Round k's time of day: k dt seconds after midnight (a run starts at 00:00:00), modulo a day.
double time_of_day_s(std::uint64_t k, double time_step_s);

/// One node's pictures as CAT062 blocks, each track under the number the node gave it.
class PictureCat062 {
 public:
  explicit PictureCat062(const Scenario& scenario)
      : source_(system_source(scenario)),
        anchor_(scenario.anchor),
        time_step_s_(scenario.time_step_s) {}

  /// Round k's picture as CAT062 blocks, each within one unfragmented UDP datagram (65 507
  /// octets); none for a picture without tracks.
  std::vector<asterix::Bytes> blocks(std::uint64_t k, const wire::PictureRound& round);

  /// Tracks left out because an item could not hold a value (beyond I062/185's ±8 192 m/s,
  /// say), and tracks without a number (more than 65 535 at once), over every round.
  std::size_t left_out() const { return left_out_; }

 private:
  asterix::DataSource source_;
  GeoAnchor anchor_;
  double time_step_s_;
  std::size_t left_out_ = 0;
};

/// A node's `--asterix-out`: its picture each round as CAT062 datagrams to one UDP destination
/// (unicast or multicast).
class PictureAsterixOut {
 public:
  PictureAsterixOut(const asterix::UdpEndpoint& destination, const Scenario& scenario)
      : cat062_(scenario), sender_(destination) {}

  /// Round k's picture, its tracks numbered (transport::number_round).
  void send(std::uint64_t k, const wire::PictureRound& round) {
    for (const asterix::Bytes& block : cat062_.blocks(k, round)) sender_.send(block);
  }

  const asterix::UdpSender& sender() const { return sender_; }
  std::size_t left_out() const { return cat062_.left_out(); }

 private:
  PictureCat062 cat062_;
  asterix::UdpSender sender_;
};

/// What a node's `--asterix-out` sent, for its log as its run ends: datagrams sent, those the
/// system refused, tracks left out.
std::string asterix_out_summary(const PictureAsterixOut& out);

/// A node's `--asterix-out` to `destination` ("HOST:PORT"); none where it is empty. Throws
/// std::invalid_argument for a destination that is no IPv4 address and port, and
/// std::runtime_error where no socket can be opened.
std::unique_ptr<PictureAsterixOut> make_asterix_out(const std::string& destination,
                                                    const Scenario& scenario);

}  // namespace skyfuse::transport
