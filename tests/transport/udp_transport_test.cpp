// The built-in loopback UDP participant. The one-to-many topics travel by multicast: a real
// tick written by this process reaches a real skyfuse-echo process through the tick topic's
// multicast group, and a plain socket joined to that group sees the same datagram. Large runs
// need large socket buffers, and the user hears when the kernel grants less.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "skyfuse/transport/dds_node.hpp"
#include "support/process.hpp"

namespace skyfuse::transport {
namespace {

using namespace std::chrono_literals;
using test::eventually;
using test::Process;

const std::filesystem::path kWork = SKYFUSE_TEST_WORK_DIR;

// A UDP socket that receives what is sent to `group`:`port` on the loopback interface.
class MulticastListener {
 public:
  MulticastListener(const char* group, int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    const int yes = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    const timeval timeout{0, 200'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    ::inet_pton(AF_INET, group, &address.sin_addr);
    bound_ = ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
    ip_mreq membership{};
    ::inet_pton(AF_INET, group, &membership.imr_multiaddr);
    ::inet_pton(AF_INET, "127.0.0.1", &membership.imr_interface);
    joined_ = ::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) == 0;
  }
  ~MulticastListener() { ::close(fd_); }
  MulticastListener(const MulticastListener&) = delete;
  MulticastListener& operator=(const MulticastListener&) = delete;

  bool ready() const { return fd_ >= 0 && bound_ && joined_; }
  /// The next datagram, empty after 200 ms without one.
  std::string receive() {
    std::array<char, 65536> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    return n > 0 ? std::string(buffer.data(), static_cast<std::size_t>(n)) : std::string();
  }

 private:
  int fd_;
  bool bound_ = false;
  bool joined_ = false;
};

std::string bytes_of(std::uint64_t value) {
  std::string bytes(sizeof value, '\0');
  std::memcpy(bytes.data(), &value, sizeof value);  // CDR little endian, as on this host
  return bytes;
}

TEST(Multicast, OneToManyTopicsHaveAPortEachBetweenTheDomainsStandardPorts) {
  for (const int domain : {0, 1, 232}) {
    const int user_multicast = 7401 + 250 * domain;  // RTPS port mapping, PB 7400, DG 250
    const int first_unicast = 7410 + 250 * domain;
    const auto tick = multicast_port("skyfuse_tick", domain);
    const auto measurement = multicast_port("skyfuse_measurement", domain);
    const auto increment = multicast_port("skyfuse_increment", domain);
    const auto picture_scan = multicast_port("skyfuse_picture_scan", domain);
    ASSERT_TRUE(tick && measurement && increment && picture_scan);
    const std::vector<int> ports = {*tick, *measurement, *increment, *picture_scan};
    for (const int port : ports) {
      EXPECT_GT(port, user_multicast);
      EXPECT_LT(port, first_unicast);
    }
    EXPECT_EQ(std::set<int>(ports.begin(), ports.end()).size(), ports.size()) << "a port each";
  }
  EXPECT_FALSE(multicast_port("skyfuse_track", 0));
  EXPECT_FALSE(multicast_port("skyfuse_status", 0));
  EXPECT_FALSE(multicast_port("skyfuse_echo", 0));
}

TEST(ReceiveBuffers, AWarningNamesTheKernelsCapOnlyWhenALargeRunNeedsMore) {
  const auto cap = receive_buffer_cap();
  ASSERT_TRUE(cap) << "no /proc/sys/net/core/rmem_max";
  EXPECT_FALSE(receive_buffer_warning(4)) << "small runs fit in any buffer";
  const auto warning = receive_buffer_warning(64);
  EXPECT_EQ(warning.has_value(), *cap < kReceiveBufferBytes);
  if (warning) {
    EXPECT_NE(warning->find(std::to_string(*cap)), std::string::npos) << *warning;
    EXPECT_NE(warning->find("sysctl -w net.core.rmem_max="), std::string::npos) << *warning;
  }
}

TEST(Multicast, ATickReachesARemoteReaderThroughTheTopicsGroup) {
  const int domain = 180;
  const std::uint64_t run_id = 0x5eed'0000'0180ULL;
  MulticastListener listener(kMulticastGroup, *multicast_port("skyfuse_tick", domain));
  ASSERT_TRUE(listener.ready()) << std::strerror(errno);

  NodeConfig config;
  config.domain_id = domain;
  config.name = "multicast-test";
  DdsNode node(config);
  auto ticks = node.make_writer<wire::Tick>();
  auto echoes = node.make_reader<wire::Echo>();
  std::filesystem::create_directories(kWork);
  Process echo({std::string(SKYFUSE_BIN_DIR) + "/skyfuse-echo", "--id", "1", "--domain",
                std::to_string(domain), "--run-id", std::to_string(run_id), "--idle-timeout", "20"},
               kWork / "multicast_echo.log");
  ASSERT_TRUE(eventually([&] { return ticks.matched() >= 1 && echoes.matched() >= 1; }, 20s))
      << echo.output();

  wire::Tick tick;
  tick.run_id(run_id);
  tick.step(7);
  // The reader may match a moment before it listens: send again until both sides saw a tick.
  bool on_group = false;
  bool echoed = false;
  for (int attempt = 0; attempt < 25 && !(on_group && echoed); ++attempt) {
    ticks.write(tick);
    for (std::string datagram = listener.receive(); !datagram.empty();
         datagram = listener.receive()) {
      if (datagram.rfind("RTPS", 0) == 0 && datagram.find(bytes_of(run_id)) != std::string::npos) {
        on_group = true;
      }
    }
    wire::Echo reply;
    while (echoes.take(reply)) echoed = echoed || (reply.run_id() == run_id && reply.step() == 7);
  }
  EXPECT_TRUE(on_group) << "no RTPS datagram with the tick on " << kMulticastGroup << ":"
                        << *multicast_port("skyfuse_tick", domain);
  EXPECT_TRUE(echoed) << echo.output();
  echo.signal(SIGTERM);
  EXPECT_TRUE(echo.wait(10s));
}

// Last in this file: profiles loaded into Fast DDS stay loaded for the rest of the process.
TEST(Multicast, AUserParticipantProfileKeepsEveryTopicUnicast) {
  EXPECT_TRUE(QosProfiles(std::nullopt, false, 181).multicast());
  std::filesystem::create_directories(kWork);
  const auto xml = kWork / "participant_profile.xml";
  std::ofstream(xml) << R"(<?xml version="1.0" encoding="UTF-8"?>
<profiles xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <participant profile_name="skyfuse_participant"><rtps/></participant>
</profiles>
)";
  EXPECT_FALSE(QosProfiles(xml, false, 181).multicast());
}

}  // namespace
}  // namespace skyfuse::transport
