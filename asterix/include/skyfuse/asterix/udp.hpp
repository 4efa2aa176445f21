#pragma once
// ASTERIX over UDP, as surveillance networks carry it: a destination given as "HOST:PORT"
// (IPv4, unicast or multicast) and a sender of datagrams to it. POSIX sockets; no DDS.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "skyfuse/asterix/pcap.hpp"

namespace skyfuse::asterix {

/// "A.B.C.D:PORT" (a dotted IPv4 address and a port in 1–65535) as an endpoint; nullopt, with
/// why in `error`, for anything else.
std::optional<UdpEndpoint> parse_udp_endpoint(std::string_view text, std::string& error);

/// Whether `endpoint` is an IPv4 multicast group (224.0.0.0/4).
bool is_multicast(const UdpEndpoint& endpoint);

/// A UDP socket that sends datagrams to one destination. To a multicast group it sends with a
/// time-to-live of `multicast_ttl` (1: the local network) and loops them back to this host's
/// own listeners, so a display on the same machine receives them too.
class UdpSender {
 public:
  /// Throws std::runtime_error naming the destination where no socket can be opened.
  explicit UdpSender(const UdpEndpoint& destination, int multicast_ttl = 1);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  /// Sends one datagram; false where the system refused it (counted in failed()). A datagram
  /// that is lost on the way is UDP's: nobody is told.
  bool send(std::span<const std::uint8_t> payload);

  std::size_t sent() const { return sent_; }
  std::size_t failed() const { return failed_; }
  const UdpEndpoint& destination() const { return destination_; }

 private:
  UdpEndpoint destination_;
  int socket_ = -1;
  std::size_t sent_ = 0;
  std::size_t failed_ = 0;
};

/// A UDP socket bound to a port on every local address (and, for a multicast group, joined to
/// it), that receives datagrams: what a test or a display listens with.
class UdpReceiver {
 public:
  /// Binds `port` (0: one the system picks; port() tells which), joining `group` where given.
  /// Throws std::runtime_error where it cannot.
  explicit UdpReceiver(std::uint16_t port, std::optional<UdpEndpoint> group = std::nullopt);
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  std::uint16_t port() const { return port_; }
  /// Asks the system for a receive buffer of `octets`: a feed that comes in bursts (a radar's
  /// scan, a round of reports at once) is lost past the buffer while the reader is busy. The
  /// system grants at most its limit (net.core.rmem_max on Linux); returns what it granted.
  std::size_t request_receive_buffer(std::size_t octets);
  /// The next datagram, waiting at most `timeout_ms`; nullopt where none came.
  std::optional<Bytes> receive(int timeout_ms);

 private:
  int socket_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace skyfuse::asterix
