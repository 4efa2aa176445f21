#pragma once
/// \file
/// Where a node's DDS traffic goes: the interface its sockets use (loopback by default: one
/// host, nothing leaves it) and how it finds the run's other participants (multicast, or a
/// discovery server where multicast does not reach). A deployment choice, the same for every
/// node of a run but the interface, which is each host's own.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace CLI {
class App;
class Option;
}

namespace skyfuse::options {

/// An IPv4 address and a UDP port, as "ADDRESS:PORT".
struct Ipv4Endpoint {
  std::string address;
  std::uint16_t port = 0;

  std::string to_string() const;
  bool operator==(const Ipv4Endpoint&) const = default;
};

/// Whether `text` is a dotted-quad IPv4 address ("10.0.0.1"), and nothing else.
bool is_ipv4_address(std::string_view text);
/// "ADDRESS:PORT" with an IPv4 address and a port in [1, 65535]; nothing if the text is not.
std::optional<Ipv4Endpoint> parse_ipv4_endpoint(std::string_view text);

/// The UDP port the harness serves discovery on for `--hosts`, on the bridge's address.
inline constexpr std::uint16_t kDefaultDiscoveryPort = 11811;

struct NetworkOptions {
  /// The address of the interface the participant's sockets use (`--interface`).
  std::string interface_address = "127.0.0.1";
  /// Discover the run's participants through the server there (`--discovery-server`) instead
  /// of by multicast; then no topic uses multicast either. `skyfuse run` serves it itself.
  std::optional<Ipv4Endpoint> discovery_server;

  bool operator==(const NetworkOptions&) const = default;
};

/// `--interface ADDRESS` and `--discovery-server ADDRESS:PORT` into `options`.
void add_network_options(CLI::App& app, NetworkOptions& options);
/// `--host-discovery server|multicast`: how the processes of a run on simulated hosts discover
/// each other, through the harness's discovery server or by multicast across the hosts' bridge.
/// Sets `multicast`; its value on entry is the default shown in the help.
CLI::Option* add_host_discovery_option(CLI::App& app, bool& multicast, const std::string& help);
/// The arguments that give a node the same network options (none for the defaults).
std::vector<std::string> network_arguments(const NetworkOptions& options);

}  // namespace skyfuse::options
