#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "pcap_format.hpp"
#include "skyfuse/asterix/pcap.hpp"
#include "skyfuse/asterix/pcap_stream.hpp"

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

bool starts_like_pcap(std::span<const std::uint8_t> first) {
  if (first.size() < 4) return false;
  const FileOrder little;
  const FileOrder big{true};
  for (const FileOrder& order : {little, big}) {
    const std::uint32_t magic = order.u32(first, 0);
    if (magic == kMagicMicroseconds || magic == kMagicNanoseconds || magic == kMagicPcapng) {
      return true;
    }
  }
  return false;
}

PcapStream::PcapStream(std::istream& in) : in_(in) {
  std::array<std::uint8_t, kFileHeaderOctets> header{};
  in_.read(reinterpret_cast<char*>(header.data()), header.size());
  if (in_.gcount() != static_cast<std::streamsize>(header.size())) {
    fail("shorter than a pcap file header (24 octets)");
    return;
  }
  FileOrder order;
  const std::uint32_t magic = order.u32(header, 0);
  if (magic == kMagicMicroseconds || magic == kMagicNanoseconds) {
    nanoseconds_ = magic == kMagicNanoseconds;
  } else {
    order.swapped = true;
    const std::uint32_t swapped = order.u32(header, 0);
    if (swapped == kMagicMicroseconds || swapped == kMagicNanoseconds) {
      nanoseconds_ = swapped == kMagicNanoseconds;
    } else if (magic == kMagicPcapng) {
      fail("a pcapng file, not classic pcap (editcap -F pcap converts it)");
      return;
    } else {
      fail("not a pcap file (unknown magic number)");
      return;
    }
  }
  swapped_ = order.swapped;
  link_ = order.u32(header, 20) & 0x0FFFFFFFu;  // upper bits: FCS flags
  if (link_ != kLinkEthernet && link_ != kLinkRaw && link_ != kLinkIpv4 &&
      link_ != kLinkLinuxCooked) {
    fail("link type " + std::to_string(link_) +
         " (only Ethernet, raw IPv4 and Linux cooked are read)");
  }
}

bool PcapStream::fail(std::string why) {
  if (!error_) error_ = std::move(why);
  return false;
}

std::optional<UdpDatagram> PcapStream::next() {
  const FileOrder order{swapped_};
  while (!error_) {
    std::array<std::uint8_t, kRecordHeaderOctets> header{};
    in_.read(reinterpret_cast<char*>(header.data()), header.size());
    if (in_.gcount() == 0) return std::nullopt;  // the end, between records
    if (in_.gcount() != static_cast<std::streamsize>(header.size())) {
      fail("a packet record header past the end of the file");
      return std::nullopt;
    }
    const std::uint32_t seconds = order.u32(header, 0);
    const std::uint32_t fraction = order.u32(header, 4);
    const std::size_t captured = order.u32(header, 8);
    frame_.resize(captured);
    in_.read(reinterpret_cast<char*>(frame_.data()), static_cast<std::streamsize>(captured));
    if (in_.gcount() != static_cast<std::streamsize>(captured)) {
      fail("a packet of " + std::to_string(captured) + " octets past the end of the file");
      return std::nullopt;
    }
    UdpDatagram d;
    d.time_ns = std::int64_t{seconds} * 1'000'000'000 +
                (nanoseconds_ ? std::int64_t{fraction} : std::int64_t{fraction} * 1000);
    const auto ip = ipv4_of(frame_, link_, skipped_);
    if (!ip) continue;
    if (const auto skip = why_not_udp(*ip)) {
      ++(skipped_.*skip);
      continue;
    }
    read_udp(*ip, d);
    return d;
  }
  return std::nullopt;
}

namespace {

PcapContents read_all(std::istream& in) {
  PcapStream stream(in);
  PcapContents contents;
  while (auto d = stream.next()) contents.datagrams.push_back(std::move(*d));
  contents.skipped = stream.skipped();
  contents.error = stream.error();
  return contents;
}

}  // namespace

PcapContents read_pcap(std::span<const std::uint8_t> file) {
  std::istringstream in(std::string(file.begin(), file.end()));
  return read_all(in);
}

PcapContents read_pcap(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    PcapContents contents;
    contents.error = "cannot open " + path.string();
    return contents;
  }
  return read_all(in);
}

}  // namespace skyfuse::asterix
