#include "skyfuse/transport/port_probe.hpp"

#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

#include "skyfuse/options/network_options.hpp"
#include "skyfuse/transport/qos.hpp"

namespace skyfuse::transport {
namespace {

// Whether a UDP socket with SO_REUSEADDR, as Fast DDS opens its multicast inputs, can bind
// `port` on every address; errno's text if not.
std::optional<std::string> bind_error(int port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return std::string(std::strerror(errno));
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  std::optional<std::string> error;
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = std::strerror(errno);
  }
  ::close(fd);
  return error;
}

}  // namespace

std::optional<std::string> taken_multicast_port(int domain_id) {
  const int base = options::kRtpsPortBase + options::kRtpsDomainGain * domain_id;
  std::vector<std::pair<int, std::string>> ports = {{base, "discovery multicast"},
                                                    {base + 1, "user multicast"}};
  for (const std::string_view topic :
       {"skyfuse_tick", "skyfuse_measurement", "skyfuse_increment", "skyfuse_picture_scan"}) {
    if (const auto port = multicast_port(topic, domain_id)) {
      ports.emplace_back(*port, std::string(topic) + " multicast");
    }
  }
  for (const auto& [port, what] : ports) {
    if (const auto error = bind_error(port)) {
      return fmt::format(
          "UDP port {} (domain {}'s {}) is held by another socket that does not share it ({}); "
          "the samples sent to it would never arrive. Choose another --domain (below 102 its "
          "ports lie outside Linux's ephemeral range), or find the holder with `ss -uanp "
          "sport = :{}`",
          port, domain_id, what, *error, port);
    }
  }
  return std::nullopt;
}

}  // namespace skyfuse::transport
