#pragma once
// Classic pcap files (the libpcap format Wireshark and tcpdump read, not pcapng) of UDP
// datagrams over IPv4: the writer makes the frames Ethernet II → IPv4 → UDP with both
// checksums, timestamps in nanoseconds (magic 0xa1b23c4d); the reader takes what a capture of
// ASTERIX usually is — Ethernet (optionally one 802.1Q tag), raw IPv4 or Linux cooked (SLL)
// frames, either byte order, micro- or nanosecond stamps — and counts what it skips.

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skyfuse/asterix/bytes.hpp"

namespace skyfuse::asterix {

struct UdpEndpoint {
  std::array<std::uint8_t, 4> address{};  ///< IPv4, network order: {127, 0, 0, 1}
  std::uint16_t port = 0;
  bool operator==(const UdpEndpoint&) const = default;
};

/// The most one IPv4 UDP datagram carries unfragmented: 65 535 less the IPv4 (20) and UDP (8)
/// headers. A block of ASTERIX meant for one datagram is framed to it (encode_blocks).
inline constexpr std::size_t kMaxUdpPayload = 65'507;

struct UdpDatagram {
  std::int64_t time_ns = 0;  ///< capture time, ns since the Unix epoch (≥ 0)
  UdpEndpoint source;
  UdpEndpoint destination;
  Bytes payload;  ///< at most 65 507 octets (one IPv4 datagram, unfragmented)
};

/// Writes a pcap file; throws std::runtime_error naming the file when it cannot be written,
/// std::invalid_argument for a datagram it cannot frame (payload too long, time before 1970 or
/// past 2106).
class PcapWriter {
 public:
  explicit PcapWriter(const std::filesystem::path& path);
  void write(const UdpDatagram& datagram);
  /// Flushes and closes; throws if the file could not be written. Later calls do nothing.
  void close();

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::uint16_t ip_id_ = 0;
};

/// Frames a pcap reader skips, by kind.
struct PcapSkips {
  std::uint64_t not_ipv4 = 0;    ///< another ethertype / IP version
  std::uint64_t not_udp = 0;     ///< another IP protocol
  std::uint64_t fragment = 0;    ///< an IPv4 fragment (not reassembled)
  std::uint64_t truncated = 0;   ///< captured shorter than its headers say (snaplen)
  std::uint64_t bad_header = 0;  ///< IHL < 5, lengths that contradict each other
  std::uint64_t total() const { return not_ipv4 + not_udp + fragment + truncated + bad_header; }
};

struct PcapContents {
  std::vector<UdpDatagram> datagrams;
  PcapSkips skipped;
  /// Set when the file as a whole was refused (not pcap, pcapng, an unknown link type, a
  /// record header past the end); datagrams then holds what came before.
  std::optional<std::string> error;
};

PcapContents read_pcap(std::span<const std::uint8_t> file);
PcapContents read_pcap(const std::filesystem::path& path);

}  // namespace skyfuse::asterix
