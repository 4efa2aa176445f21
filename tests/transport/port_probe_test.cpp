// A multicast port of the domain held by a socket that does not share it: Fast DDS would open
// the domain anyway and lose every sample sent there; the node refuses to start, naming it.
#include "skyfuse/transport/port_probe.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "skyfuse/transport/dds_node.hpp"
#include "skyfuse/transport/qos.hpp"

namespace skyfuse::transport {
namespace {

using ::testing::HasSubstr;

constexpr int kDomain = 229;

// A plain UDP socket on `port`, as an ephemeral send socket of some process would be.
class HeldPort {
 public:
  explicit HeldPort(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    bound_ = ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~HeldPort() { ::close(fd_); }
  HeldPort(const HeldPort&) = delete;
  HeldPort& operator=(const HeldPort&) = delete;
  bool bound() const { return bound_; }

 private:
  int fd_;
  bool bound_ = false;
};

TEST(PortProbe, ANodeRefusesADomainWhoseIncrementPortAnotherSocketHolds) {
  EXPECT_EQ(taken_multicast_port(kDomain), std::nullopt) << "the domain's ports are free";
  const int port = *multicast_port("skyfuse_increment", kDomain);
  const HeldPort held(port);
  ASSERT_TRUE(held.bound());
  const auto taken = taken_multicast_port(kDomain);
  ASSERT_TRUE(taken.has_value());
  EXPECT_THAT(*taken, HasSubstr(std::to_string(port)));
  EXPECT_THAT(*taken, HasSubstr("skyfuse_increment"));
  NodeConfig config;
  config.domain_id = kDomain;
  config.name = "port-probe";
  EXPECT_THROW(DdsNode node(config), DdsError);
}

TEST(PortProbe, NodesOfOneDomainShareItsPorts) {
  NodeConfig config;
  config.domain_id = kDomain + 1;
  config.name = "port-probe-first";
  const DdsNode first(config);
  config.name = "port-probe-second";
  EXPECT_NO_THROW(DdsNode second(config));
}

}  // namespace
}  // namespace skyfuse::transport
