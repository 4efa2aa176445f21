#pragma once
// The numbers of the classic pcap format (the libpcap file format: a 24-octet file header,
// then per packet a 16-octet record header and the captured octets) and of the frames the
// writer and reader handle. Internal to the library.

#include <cstddef>
#include <cstdint>

#include "skyfuse/asterix/pcap.hpp"

namespace skyfuse::asterix::pcap {

inline constexpr std::uint32_t kMagicMicroseconds = 0xA1B2C3D4u;
inline constexpr std::uint32_t kMagicNanoseconds = 0xA1B23C4Du;
inline constexpr std::uint32_t kMagicPcapng = 0x0A0D0D0Au;  // a pcapng Section Header Block
inline constexpr std::size_t kFileHeaderOctets = 24;
inline constexpr std::size_t kRecordHeaderOctets = 16;
inline constexpr std::uint32_t kSnapLength = 262144;  // what tcpdump and Wireshark default to

// Link types (tcpdump.org/linktypes.html).
inline constexpr std::uint32_t kLinkEthernet = 1;
inline constexpr std::uint32_t kLinkRaw = 101;  // raw IP; a version nibble tells 4 from 6
inline constexpr std::uint32_t kLinkLinuxCooked = 113;
inline constexpr std::uint32_t kLinkIpv4 = 228;

inline constexpr std::size_t kEthernetOctets = 14;
inline constexpr std::size_t kVlanTagOctets = 4;
inline constexpr std::size_t kLinuxCookedOctets = 16;
inline constexpr std::uint16_t kEthertypeIpv4 = 0x0800;
inline constexpr std::uint16_t kEthertypeVlan = 0x8100;
inline constexpr std::size_t kIpv4HeaderOctets = 20;  // without options, as the writer sends
inline constexpr std::uint8_t kProtocolUdp = 17;
inline constexpr std::size_t kUdpHeaderOctets = 8;
static_assert(asterix::kMaxUdpPayload == 65535 - kIpv4HeaderOctets - kUdpHeaderOctets);

}  // namespace skyfuse::asterix::pcap
