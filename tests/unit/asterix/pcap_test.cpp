// The pcap writer against the file format (header, record headers, Ethernet/IPv4/UDP with their
// checksums), and the reader: what the writer wrote, other captures' variants, and refusals.
#include "skyfuse/asterix/pcap.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "skyfuse/asterix/pcap_stream.hpp"

namespace skyfuse::asterix {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "skyfuse_asterix_pcap_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<UdpDatagram> sample_datagrams() {
  return {
      {1'700'000'000'123'456'789, {{10, 0, 0, 1}, 40000}, {{239, 1, 2, 3}, 8600}, {62, 0, 4, 0}},
      {1'700'000'001'000'000'000,
       {{10, 0, 0, 2}, 40001},
       {{127, 0, 0, 1}, 8600},
       Bytes(1000, 0xAB)},
      {1'700'000'002'000'000'001, {{10, 0, 0, 3}, 5}, {{192, 168, 1, 9}, 6}, Bytes{}},
  };
}

// The one's complement sum of 16-bit words, as RFC 1071 checks a header: 0xFFFF when right.
std::uint32_t checksum_sum(const Bytes& bytes, std::size_t from, std::size_t to,
                           std::uint32_t sum) {
  for (std::size_t i = from; i + 1 < to; i += 2) sum += std::uint32_t{bytes[i]} << 8 | bytes[i + 1];
  if ((to - from) % 2 != 0) sum += std::uint32_t{bytes[to - 1]} << 8;
  while (sum > 0xFFFF) sum = (sum & 0xFFFF) + (sum >> 16);
  return sum;
}

TEST(AsterixPcap, WritesAClassicNanosecondEthernetFile) {
  const auto path = scratch("layout.pcap");
  PcapWriter writer(path);
  writer.write(sample_datagrams()[0]);
  writer.close();
  const auto file = read_file(path);
  // Header: magic 0xa1b23c4d (nanoseconds) little-endian, version 2.4, snaplen 262144, link 1.
  ASSERT_GE(file.size(), 24u + 16u);
  EXPECT_EQ(Bytes(file.begin(), file.begin() + 8), (Bytes{0x4D, 0x3C, 0xB2, 0xA1, 2, 0, 4, 0}));
  EXPECT_EQ(Bytes(file.begin() + 16, file.begin() + 24), (Bytes{0, 0, 4, 0, 1, 0, 0, 0}));
  // Record: 14 Ethernet + 20 IPv4 + 8 UDP + 4 payload = 46 octets, captured whole.
  EXPECT_EQ(file[24 + 8], 46);
  EXPECT_EQ(file[24 + 12], 46);
  ASSERT_EQ(file.size(), 24u + 16u + 46u);
  const std::size_t eth = 40, ip = eth + 14, udp = ip + 20;
  // A multicast group's MAC: 01:00:5e and its low 23 bits (1.2.3).
  EXPECT_EQ(Bytes(file.begin() + eth, file.begin() + eth + 6), (Bytes{1, 0, 0x5E, 1, 2, 3}));
  EXPECT_EQ(file[eth + 12], 0x08);  // IPv4
  EXPECT_EQ(file[ip], 0x45);
  EXPECT_EQ(file[ip + 9], 17);  // UDP
  EXPECT_EQ(checksum_sum(file, ip, ip + 20, 0), 0xFFFFu);
  // UDP: the pseudo-header (addresses, protocol, length) and the datagram sum to 0xFFFF.
  const std::uint32_t pseudo = checksum_sum(file, ip + 12, ip + 20, 17 + 12);
  EXPECT_EQ(checksum_sum(file, udp, udp + 12, pseudo), 0xFFFFu);
}

TEST(AsterixPcap, ReadsBackWhatItWrote) {
  const auto path = scratch("round_trip.pcap");
  const auto written = sample_datagrams();
  {
    PcapWriter writer(path);
    for (const auto& d : written) writer.write(d);
  }  // the destructor closes the file
  const auto read = read_pcap(path);
  ASSERT_FALSE(read.error) << *read.error;
  ASSERT_EQ(read.datagrams.size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_EQ(read.datagrams[i].time_ns, written[i].time_ns);
    EXPECT_EQ(read.datagrams[i].source, written[i].source);
    EXPECT_EQ(read.datagrams[i].destination, written[i].destination);
    EXPECT_EQ(read.datagrams[i].payload, written[i].payload);
  }
  EXPECT_EQ(read.skipped.total(), 0u);
}

// The stream gives the same datagrams one at a time, and where the file is cut in a frame it
// gives those before and then says why it stopped.
TEST(AsterixPcap, StreamsTheSameDatagramsOneAtATime) {
  const auto path = scratch("streamed.pcap");
  const auto written = sample_datagrams();
  {
    PcapWriter writer(path);
    for (const auto& d : written) writer.write(d);
  }
  std::ifstream in(path, std::ios::binary);
  PcapStream stream(in);
  ASSERT_FALSE(stream.error()) << *stream.error();
  std::size_t i = 0;
  while (const auto d = stream.next()) {
    ASSERT_LT(i, written.size());
    EXPECT_EQ(d->time_ns, written[i].time_ns);
    EXPECT_EQ(d->source, written[i].source);
    EXPECT_EQ(d->payload, written[i].payload);
    ++i;
  }
  EXPECT_EQ(i, written.size());
  EXPECT_FALSE(stream.error());

  std::ifstream whole(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(whole)), std::istreambuf_iterator<char>());
  bytes.resize(bytes.size() - 3);  // the last frame cut short
  std::istringstream cut(bytes);
  PcapStream short_of(cut);
  std::size_t read = 0;
  while (short_of.next()) ++read;
  EXPECT_EQ(read, written.size() - 1);
  ASSERT_TRUE(short_of.error());
  EXPECT_NE(short_of.error()->find("past the end of the file"), std::string::npos);
}

TEST(AsterixPcap, RefusesWhatItCannotFrame) {
  PcapWriter writer(scratch("refused.pcap"));
  UdpDatagram d = sample_datagrams()[0];
  d.payload.assign(65508, 0);
  EXPECT_THROW(writer.write(d), std::invalid_argument);
  d.payload.clear();
  d.time_ns = -1;
  EXPECT_THROW(writer.write(d), std::invalid_argument);
  EXPECT_THROW(PcapWriter(scratch("no/such/dir.pcap")), std::runtime_error);
}

// A big-endian microsecond file of raw IPv4 (link 228), as another host's capture may be.
Bytes big_endian_raw_ipv4(std::uint8_t protocol, std::uint8_t flags) {
  Bytes file{0xA1, 0xB2, 0xC3, 0xD4, 0, 2, 0,    4,    0, 0, 0, 0,
             0,    0,    0,    0,    0, 0, 0xFF, 0xFF, 0, 0, 0, 228};
  const Bytes packet{0x45, 0,    0,    31,   0, 0,  flags, 0, 64, protocol,
                     0,    0,    10,   0,    0, 1,  10,    0, 0,  2,  // IPv4
                     0x9C, 0x40, 0x21, 0x98, 0, 11, 0,     0,  // UDP 40000 → 8600, length 11
                     62,   0,    3};
  const Bytes record{0, 0, 0, 100, 0, 0, 0x03, 0xE8, 0, 0, 0, 31, 0, 0, 0, 31};  // 100 s, 1000 us
  file.insert(file.end(), record.begin(), record.end());
  file.insert(file.end(), packet.begin(), packet.end());
  return file;
}

TEST(AsterixPcap, TellsAPcapByItsFirstFourOctets) {
  EXPECT_TRUE(starts_like_pcap(big_endian_raw_ipv4(17, 0)));        // big-endian microseconds
  EXPECT_TRUE(starts_like_pcap(Bytes{0x4D, 0x3C, 0xB2, 0xA1}));     // little-endian nanoseconds
  EXPECT_TRUE(starts_like_pcap(Bytes{0x0A, 0x0D, 0x0D, 0x0A, 0}));  // pcapng: refused by name
  EXPECT_FALSE(starts_like_pcap(Bytes{48, 0, 11, 0xF0}));           // a CAT048 data block
  EXPECT_FALSE(starts_like_pcap(Bytes{0xA1, 0xB2}));                // too short to say
}

TEST(AsterixPcap, ReadsOtherByteOrdersAndLinkTypes) {
  const auto read = read_pcap(big_endian_raw_ipv4(17, 0));
  ASSERT_FALSE(read.error) << *read.error;
  ASSERT_EQ(read.datagrams.size(), 1u);
  EXPECT_EQ(read.datagrams[0].time_ns, 100'001'000'000);
  EXPECT_EQ(read.datagrams[0].destination.port, 8600);
  EXPECT_EQ(read.datagrams[0].payload, (Bytes{62, 0, 3}));
}

TEST(AsterixPcap, SkipsWhatIsNotAWholeUdpDatagramAndSaysWhy) {
  EXPECT_EQ(read_pcap(big_endian_raw_ipv4(6, 0)).skipped.not_udp, 1u);       // TCP
  EXPECT_EQ(read_pcap(big_endian_raw_ipv4(17, 0x20)).skipped.fragment, 1u);  // more fragments
  auto cut = big_endian_raw_ipv4(17, 0);
  cut[24 + 11] = 25;  // captured 25 of the packet's 31 octets
  cut.resize(cut.size() - 6);
  EXPECT_EQ(read_pcap(cut).skipped.truncated, 1u);
}

TEST(AsterixPcap, RefusesFilesItCannotRead) {
  EXPECT_TRUE(read_pcap(Bytes{0xA1, 0xB2}).error);
  const Bytes pcapng{0x0A, 0x0D, 0x0D, 0x0A, 0, 0, 0, 0, 0, 0, 0, 0,
                     0,    0,    0,    0,    0, 0, 0, 0, 0, 0, 0, 0};
  const auto ng = read_pcap(pcapng);
  ASSERT_TRUE(ng.error);
  EXPECT_NE(ng.error->find("pcapng"), std::string::npos);
  auto wifi = big_endian_raw_ipv4(17, 0);
  wifi[23] = 105;  // IEEE 802.11
  EXPECT_TRUE(read_pcap(wifi).error);
  auto past_end = big_endian_raw_ipv4(17, 0);
  past_end.pop_back();  // the record says 31 octets; 30 remain
  const auto partial = read_pcap(past_end);
  EXPECT_TRUE(partial.error);
  EXPECT_TRUE(partial.datagrams.empty());
  EXPECT_TRUE(read_pcap(scratch("does_not_exist.pcap")).error);
}

}  // namespace
}  // namespace skyfuse::asterix
