#include "skyfuse/asterix/udp.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>

namespace skyfuse::asterix {
namespace {

std::string describe(const UdpEndpoint& e) {
  return std::to_string(e.address[0]) + "." + std::to_string(e.address[1]) + "." +
         std::to_string(e.address[2]) + "." + std::to_string(e.address[3]) + ":" +
         std::to_string(e.port);
}

sockaddr_in socket_address(const UdpEndpoint& e) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(e.port);
  std::memcpy(&a.sin_addr.s_addr, e.address.data(), 4);  // already in network order
  return a;
}

// "'value'rest", built by appending to a string of one character: GCC 12 misreads a short
// literal it inlines into a string assignment or concatenation as an overlapping copy
// (-Wrestrict, GCC bug 105329).
std::string quoted(std::string_view value, std::string_view rest) {
  std::string s(1, '\'');
  s.append(value);
  s.push_back('\'');
  s.append(rest);
  return s;
}

[[noreturn]] void fail(const std::string& what, const UdpEndpoint& e) {
  throw std::runtime_error(what + " " + describe(e) + ": " + std::strerror(errno));
}

}  // namespace

std::optional<UdpEndpoint> parse_udp_endpoint(std::string_view text, std::string& error) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) {
    error = quoted(text, " is not HOST:PORT (an IPv4 address and a port)");
    return std::nullopt;
  }
  const std::string host(text.substr(0, colon));
  const std::string_view port_text = text.substr(colon + 1);
  UdpEndpoint endpoint;
  in_addr address{};
  if (inet_pton(AF_INET, host.c_str(), &address) != 1) {
    error = quoted(host, " is no dotted IPv4 address (for example 127.0.0.1 or 239.1.2.3)");
    return std::nullopt;
  }
  std::memcpy(endpoint.address.data(), &address.s_addr, 4);
  unsigned port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc() || end != port_text.data() + port_text.size() || port == 0 ||
      port > 65535) {
    error = quoted(port_text, " is no port in 1-65535");
    return std::nullopt;
  }
  endpoint.port = static_cast<std::uint16_t>(port);
  return endpoint;
}

bool is_multicast(const UdpEndpoint& endpoint) {
  return (endpoint.address[0] & 0xF0) == 0xE0;
}

UdpSender::UdpSender(const UdpEndpoint& destination, int multicast_ttl)
    : destination_(destination), socket_(::socket(AF_INET, SOCK_DGRAM, 0)) {
  if (socket_ < 0) fail("no UDP socket for", destination);
  if (is_multicast(destination)) {
    const unsigned char ttl = static_cast<unsigned char>(multicast_ttl);
    const unsigned char loop = 1;
    if (setsockopt(socket_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0 ||
        setsockopt(socket_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) {
      ::close(socket_);
      fail("cannot send to the multicast group", destination);
    }
  }
}

UdpSender::~UdpSender() {
  if (socket_ >= 0) ::close(socket_);
}

bool UdpSender::send(std::span<const std::uint8_t> payload) {
  const sockaddr_in to = socket_address(destination_);
  const ssize_t n = ::sendto(socket_, payload.data(), payload.size(), 0,
                             reinterpret_cast<const sockaddr*>(&to), sizeof to);
  if (n != static_cast<ssize_t>(payload.size())) {
    ++failed_;
    return false;
  }
  ++sent_;
  return true;
}

UdpReceiver::UdpReceiver(std::uint16_t port, std::optional<UdpEndpoint> group)
    : socket_(::socket(AF_INET, SOCK_DGRAM, 0)) {
  const UdpEndpoint any{{0, 0, 0, 0}, port};
  if (socket_ < 0) fail("no UDP socket for", any);
  const int reuse = 1;
  setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &reuse, sizeof reuse);
  const sockaddr_in local = socket_address(any);
  if (::bind(socket_, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    ::close(socket_);
    fail("cannot bind", any);
  }
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  getsockname(socket_, reinterpret_cast<sockaddr*>(&bound), &length);
  port_ = ntohs(bound.sin_port);
  if (group) {
    ip_mreq membership{};
    std::memcpy(&membership.imr_multiaddr.s_addr, group->address.data(), 4);
    membership.imr_interface.s_addr = htonl(INADDR_ANY);
    if (setsockopt(socket_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
      ::close(socket_);
      fail("cannot join the multicast group", *group);
    }
  }
}

std::size_t UdpReceiver::request_receive_buffer(std::size_t octets) {
  const int wanted = static_cast<int>(std::min<std::size_t>(octets, 1U << 30U));
  setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &wanted, sizeof wanted);
  int granted = 0;
  socklen_t length = sizeof granted;
  getsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &granted, &length);
  // Linux reports twice what it was asked for (it counts its own bookkeeping): say what the
  // datagrams get.
  return static_cast<std::size_t>(granted) / 2;
}

UdpReceiver::~UdpReceiver() {
  if (socket_ >= 0) ::close(socket_);
}

std::optional<Bytes> UdpReceiver::receive(int timeout_ms) {
  pollfd ready{socket_, POLLIN, 0};
  if (::poll(&ready, 1, timeout_ms) <= 0) return std::nullopt;
  Bytes datagram(65'536);
  const ssize_t n = ::recv(socket_, datagram.data(), datagram.size(), 0);
  if (n < 0) return std::nullopt;
  datagram.resize(static_cast<std::size_t>(n));
  return datagram;
}

}  // namespace skyfuse::asterix
