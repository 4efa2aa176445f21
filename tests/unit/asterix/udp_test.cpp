// ASTERIX over UDP (asterix/udp.hpp): the "HOST:PORT" a user gives, and datagrams sent and
// received over this machine's own loopback and, where it has a multicast route, a group.
#include "skyfuse/asterix/udp.hpp"

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

namespace skyfuse::asterix {
namespace {

TEST(UdpEndpoint, ReadsADottedAddressAndAPort) {
  std::string error;
  const auto endpoint = parse_udp_endpoint("239.1.2.3:8600", error);
  ASSERT_TRUE(endpoint.has_value()) << error;
  EXPECT_EQ(endpoint->address, (std::array<std::uint8_t, 4>{239, 1, 2, 3}));
  EXPECT_EQ(endpoint->port, 8600);
  EXPECT_TRUE(is_multicast(*endpoint));
  EXPECT_FALSE(is_multicast(*parse_udp_endpoint("127.0.0.1:1", error)));
}

TEST(UdpEndpoint, RefusesAnythingElseSayingWhy) {
  for (const char* text : {"8600", "localhost:8600", "10.0.0:8600", "10.0.0.1:", "10.0.0.1:0",
                           "10.0.0.1:65536", "10.0.0.1:86x0", "[::1]:8600"}) {
    std::string error;
    EXPECT_FALSE(parse_udp_endpoint(text, error).has_value()) << text;
    EXPECT_FALSE(error.empty()) << text;
  }
}

TEST(UdpSender, SendsDatagramsAReceiverOnThisHostGets) {
  UdpReceiver receiver(0);
  ASSERT_NE(receiver.port(), 0);
  UdpSender sender(UdpEndpoint{{127, 0, 0, 1}, receiver.port()});
  const Bytes first{62, 0, 3, 0xAB};
  const Bytes second(1500, 0x5A);
  ASSERT_TRUE(sender.send(first));
  ASSERT_TRUE(sender.send(second));
  EXPECT_EQ(receiver.receive(1000), first);
  EXPECT_EQ(receiver.receive(1000), second);
  EXPECT_FALSE(receiver.receive(20).has_value()) << "nothing else";
  EXPECT_EQ(sender.sent(), 2U);
  EXPECT_EQ(sender.failed(), 0U);
}

// A group: sent with the loop back on, so a listener of this host that joined it hears it.
TEST(UdpSender, SendsToAMulticastGroupThatAListenerHereJoined) {
  const UdpEndpoint group{{239, 255, 86, 0}, 0};
  std::optional<UdpReceiver> receiver;
  try {
    receiver.emplace(0, group);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "this host joins no multicast group: " << e.what();
  }
  UdpSender sender(UdpEndpoint{group.address, receiver->port()});
  const Bytes datagram{62, 0, 3, 0x01};
  if (!sender.send(datagram)) GTEST_SKIP() << "this host has no route to a multicast group";
  EXPECT_EQ(receiver->receive(1000), datagram);
}

}  // namespace
}  // namespace skyfuse::asterix
