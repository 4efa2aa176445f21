#include <algorithm>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "pcap_format.hpp"
#include "skyfuse/asterix/pcap.hpp"

namespace skyfuse::asterix {
namespace {

using namespace pcap;

std::uint32_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint32_t{b[at]} << 8 | b[at + 1];
}

// A pcap header field in the file's byte order.
struct FileOrder {
  bool swapped = false;
  std::uint32_t u32(std::span<const std::uint8_t> b, std::size_t at) const {
    const std::uint32_t le = std::uint32_t{b[at]} | std::uint32_t{b[at + 1]} << 8 |
                             std::uint32_t{b[at + 2]} << 16 | std::uint32_t{b[at + 3]} << 24;
    const std::uint32_t be = std::uint32_t{b[at]} << 24 | std::uint32_t{b[at + 1]} << 16 |
                             std::uint32_t{b[at + 2]} << 8 | std::uint32_t{b[at + 3]};
    return swapped ? be : le;
  }
};

// The IPv4 packet inside a frame of `link`, or nullopt (counted in `skipped`).
std::optional<std::span<const std::uint8_t>> ipv4_of(std::span<const std::uint8_t> frame,
                                                     std::uint32_t link, PcapSkips& skipped) {
  std::size_t at = 0;
  std::uint32_t ethertype = kEthertypeIpv4;
  if (link == kLinkEthernet) {
    at = kEthernetOctets;
    if (frame.size() >= at) ethertype = be16(frame, 12);
    if (frame.size() >= at && ethertype == kEthertypeVlan) {
      at += kVlanTagOctets;
      if (frame.size() >= at) ethertype = be16(frame, 16);
    }
  } else if (link == kLinkLinuxCooked) {
    at = kLinuxCookedOctets;
    if (frame.size() >= at) ethertype = be16(frame, 14);
  }
  if (frame.size() < at) {
    ++skipped.truncated;
    return std::nullopt;
  }
  if (ethertype != kEthertypeIpv4) {
    ++skipped.not_ipv4;
    return std::nullopt;
  }
  return frame.subspan(at);
}

// Why an IPv4 packet holds no UDP datagram this reader takes, if it does not.
std::uint64_t PcapSkips::*why_not_udp(std::span<const std::uint8_t> ip) {
  if (ip.empty()) return &PcapSkips::truncated;
  if (ip[0] >> 4 != 4) return &PcapSkips::not_ipv4;
  if (ip.size() < kIpv4HeaderOctets) return &PcapSkips::truncated;
  const std::size_t header = std::size_t{ip[0] & 0x0Fu} * 4;
  const std::size_t total = be16(ip, 2);
  if (header < kIpv4HeaderOctets || total < header + kUdpHeaderOctets) {
    return &PcapSkips::bad_header;
  }
  if (ip.size() < total) return &PcapSkips::truncated;
  const bool more_fragments = (ip[6] & 0x20u) != 0;
  const std::uint32_t offset = be16(ip, 6) & 0x1FFFu;
  if (more_fragments || offset != 0) return &PcapSkips::fragment;
  if (ip[9] != kProtocolUdp) return &PcapSkips::not_udp;
  const std::size_t length = be16(ip, header + 4);
  if (length < kUdpHeaderOctets || length > total - header) return &PcapSkips::bad_header;
  return nullptr;
}

// The UDP datagram of an IPv4 packet why_not_udp accepted.
void read_udp(std::span<const std::uint8_t> ip, UdpDatagram& d) {
  const std::size_t header = std::size_t{ip[0] & 0x0Fu} * 4;
  const auto udp = ip.subspan(header);
  const std::size_t length = be16(udp, 4);
  std::copy(ip.begin() + 12, ip.begin() + 16, d.source.address.begin());
  std::copy(ip.begin() + 16, ip.begin() + 20, d.destination.address.begin());
  d.source.port = static_cast<std::uint16_t>(be16(udp, 0));
  d.destination.port = static_cast<std::uint16_t>(be16(udp, 2));
  d.payload.assign(udp.begin() + kUdpHeaderOctets,
                   udp.begin() + static_cast<std::ptrdiff_t>(length));
}

}  // namespace

PcapContents read_pcap(std::span<const std::uint8_t> file) {
  PcapContents contents;
  if (file.size() < kFileHeaderOctets) {
    contents.error = "shorter than a pcap file header (24 octets)";
    return contents;
  }
  FileOrder order;
  const std::uint32_t magic = order.u32(file, 0);
  bool nanoseconds = false;
  if (magic == kMagicMicroseconds || magic == kMagicNanoseconds) {
    nanoseconds = magic == kMagicNanoseconds;
  } else {
    order.swapped = true;
    const std::uint32_t swapped = order.u32(file, 0);
    if (swapped == kMagicMicroseconds || swapped == kMagicNanoseconds) {
      nanoseconds = swapped == kMagicNanoseconds;
    } else if (magic == kMagicPcapng) {
      contents.error = "a pcapng file, not classic pcap (editcap -F pcap converts it)";
      return contents;
    } else {
      contents.error = "not a pcap file (unknown magic number)";
      return contents;
    }
  }
  const std::uint32_t link = order.u32(file, 20) & 0x0FFFFFFFu;  // upper bits: FCS flags
  if (link != kLinkEthernet && link != kLinkRaw && link != kLinkIpv4 && link != kLinkLinuxCooked) {
    contents.error = "link type " + std::to_string(link) +
                     " (only Ethernet, raw IPv4 and Linux cooked are read)";
    return contents;
  }
  std::size_t at = kFileHeaderOctets;
  while (at < file.size()) {
    if (file.size() - at < kRecordHeaderOctets) {
      contents.error = "a packet record header past the end of the file";
      return contents;
    }
    const std::uint32_t seconds = order.u32(file, at);
    const std::uint32_t fraction = order.u32(file, at + 4);
    const std::size_t captured = order.u32(file, at + 8);
    at += kRecordHeaderOctets;
    if (captured > file.size() - at) {
      contents.error =
          "a packet of " + std::to_string(captured) + " octets past the end of the file";
      return contents;
    }
    const auto frame = file.subspan(at, captured);
    at += captured;
    UdpDatagram d;
    d.time_ns = std::int64_t{seconds} * 1'000'000'000 +
                (nanoseconds ? std::int64_t{fraction} : std::int64_t{fraction} * 1000);
    const auto ip = ipv4_of(frame, link, contents.skipped);
    if (!ip) continue;
    if (const auto skip = why_not_udp(*ip)) {
      ++(contents.skipped.*skip);
      continue;
    }
    read_udp(*ip, d);
    contents.datagrams.push_back(std::move(d));
  }
  return contents;
}

PcapContents read_pcap(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    PcapContents contents;
    contents.error = "cannot open " + path.string();
    return contents;
  }
  const Bytes bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return read_pcap(bytes);
}

}  // namespace skyfuse::asterix
