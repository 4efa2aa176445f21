#include <stdexcept>
#include <string>

#include "pcap_format.hpp"
#include "skyfuse/asterix/pcap.hpp"

namespace skyfuse::asterix {
namespace {

using namespace pcap;

// The pcap headers are in the writer's byte order; we write little-endian on every host.
void put_le32(Bytes& out, std::uint32_t v) {
  for (unsigned i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i) & 0xFFu));
}
void put_le16(Bytes& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
// The frame's headers are in network order.
void put_be16(Bytes& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8 & 0xFFu));
  out.push_back(static_cast<std::uint8_t>(v & 0xFFu));
}

// The Internet checksum (RFC 1071): one's complement of the one's complement sum of 16-bit
// words, an odd last octet padded with zero.
std::uint32_t ones_complement_sum(std::span<const std::uint8_t> bytes, std::uint32_t sum) {
  for (std::size_t i = 0; i + 1 < bytes.size(); i += 2)
    sum += std::uint32_t{bytes[i]} << 8 | bytes[i + 1];
  if (bytes.size() % 2 != 0) sum += std::uint32_t{bytes.back()} << 8;
  while (sum > 0xFFFFu) sum = (sum & 0xFFFFu) + (sum >> 16);
  return sum;
}

// A locally administered unicast MAC for a host, or the IPv4 multicast MAC (01:00:5e and the
// group's low 23 bits) so that a multicast feed looks like one on the wire.
void put_mac(Bytes& out, const std::array<std::uint8_t, 4>& ip, std::uint8_t host) {
  const bool multicast = ip[0] >= 224 && ip[0] <= 239;
  const std::array<std::uint8_t, 6> mac =
      multicast
          ? std::array<std::uint8_t, 6>{0x01,  0x00, 0x5E, static_cast<std::uint8_t>(ip[1] & 0x7Fu),
                                        ip[2], ip[3]}
          : std::array<std::uint8_t, 6>{0x02, 0x00, 0x00, 0x00, 0x00, host};
  for (const auto octet : mac) out.push_back(octet);
}

Bytes frame(const UdpDatagram& d, std::uint16_t ip_id) {
  const std::size_t udp_length = kUdpHeaderOctets + d.payload.size();
  const std::size_t ip_length = kIpv4HeaderOctets + udp_length;
  Bytes out;
  out.reserve(kEthernetOctets + ip_length);
  put_mac(out, d.destination.address, 2);
  put_mac(out, d.source.address, 1);
  put_be16(out, kEthertypeIpv4);

  const std::size_t ip_at = out.size();
  out.push_back(0x45);  // version 4, IHL 5 (no options)
  out.push_back(0x00);  // DSCP, ECN
  put_be16(out, static_cast<std::uint32_t>(ip_length));
  put_be16(out, ip_id);
  put_be16(out, 0x4000);  // flags: don't fragment; offset 0
  out.push_back(64);      // TTL
  out.push_back(kProtocolUdp);
  put_be16(out, 0);  // header checksum, filled below
  for (const auto octet : d.source.address) out.push_back(octet);
  for (const auto octet : d.destination.address) out.push_back(octet);
  const auto ip_sum = ~ones_complement_sum({out.data() + ip_at, kIpv4HeaderOctets}, 0) & 0xFFFFu;
  out[ip_at + 10] = static_cast<std::uint8_t>(ip_sum >> 8);
  out[ip_at + 11] = static_cast<std::uint8_t>(ip_sum & 0xFFu);

  const std::size_t udp_at = out.size();
  put_be16(out, d.source.port);
  put_be16(out, d.destination.port);
  put_be16(out, static_cast<std::uint32_t>(udp_length));
  put_be16(out, 0);  // checksum, filled below
  out.insert(out.end(), d.payload.begin(), d.payload.end());
  // The UDP checksum covers a pseudo-header (addresses, protocol, UDP length) and the datagram;
  // a computed 0 is sent as 0xFFFF, since 0 means "no checksum".
  std::uint32_t pseudo = 0;
  pseudo = ones_complement_sum({out.data() + ip_at + 12, 8}, pseudo);
  pseudo += kProtocolUdp + static_cast<std::uint32_t>(udp_length);
  auto udp_sum = ~ones_complement_sum({out.data() + udp_at, udp_length}, pseudo) & 0xFFFFu;
  if (udp_sum == 0) udp_sum = 0xFFFFu;
  out[udp_at + 6] = static_cast<std::uint8_t>(udp_sum >> 8);
  out[udp_at + 7] = static_cast<std::uint8_t>(udp_sum & 0xFFu);
  return out;
}

}  // namespace

PcapWriter::PcapWriter(const std::filesystem::path& path)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot create pcap file " + path.string());
  Bytes header;
  put_le32(header, kMagicNanoseconds);
  put_le16(header, 2);  // version 2.4
  put_le16(header, 4);
  put_le32(header, 0);  // thiszone: timestamps are UTC
  put_le32(header, 0);  // sigfigs
  put_le32(header, kSnapLength);
  put_le32(header, kLinkEthernet);
  out_.write(reinterpret_cast<const char*>(header.data()),
             static_cast<std::streamsize>(header.size()));
}

void PcapWriter::write(const UdpDatagram& d) {
  if (!out_.is_open()) throw std::logic_error("pcap writer of " + path_.string() + " is closed");
  if (d.payload.size() > kMaxUdpPayload) {
    throw std::invalid_argument("UDP payload of " + std::to_string(d.payload.size()) +
                                " octets exceeds one IPv4 datagram");
  }
  constexpr std::int64_t kNs = 1'000'000'000;
  if (d.time_ns < 0 || d.time_ns / kNs > 0xFFFFFFFFll) {
    throw std::invalid_argument("pcap time must be in [1970, 2106)");
  }
  const auto bytes = frame(d, ip_id_++);
  Bytes record;
  put_le32(record, static_cast<std::uint32_t>(d.time_ns / kNs));
  put_le32(record, static_cast<std::uint32_t>(d.time_ns % kNs));
  put_le32(record, static_cast<std::uint32_t>(bytes.size()));  // captured
  put_le32(record, static_cast<std::uint32_t>(bytes.size()));  // on the wire
  record.insert(record.end(), bytes.begin(), bytes.end());
  out_.write(reinterpret_cast<const char*>(record.data()),
             static_cast<std::streamsize>(record.size()));
}

void PcapWriter::close() {
  if (!out_.is_open()) return;
  out_.close();
  if (!out_) throw std::runtime_error("could not write pcap file " + path_.string());
}

}  // namespace skyfuse::asterix
