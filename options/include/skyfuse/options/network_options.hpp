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
}  // namespace CLI

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

/// The RTPS well-known ports: domain d's start at 7400 + 250 d, and participant p listens for
/// discovery at 10 + 2 p above them and for data one port higher.
inline constexpr int kRtpsPortBase = 7400;
inline constexpr int kRtpsDomainGain = 250;
inline constexpr int kRtpsDiscoveryOffset = 10;
inline constexpr int kRtpsParticipantGain = 2;
/// The UDP port on which participant `participant_id` of `domain` listens for discovery, which
/// `--discovery-peers` lists.
inline constexpr std::uint16_t discovery_port(int domain, int participant_id) {
  return static_cast<std::uint16_t>(kRtpsPortBase + kRtpsDomainGain * domain +
                                    kRtpsDiscoveryOffset + kRtpsParticipantGain * participant_id);
}
/// Participant ids a domain has room for on one address: its 250 ports hold 120.
inline constexpr int kParticipantIdsPerAddress =
    (kRtpsDomainGain - kRtpsDiscoveryOffset) / kRtpsParticipantGain;
/// Participant ids a domain has on one address: kParticipantIdsPerAddress, fewer in the
/// highest domains, whose data ports (discovery_port() + 1) would pass 65535.
inline constexpr int participant_ids_per_address(int domain) {
  const int room = (65535 - 1 - discovery_port(domain, 0)) / kRtpsParticipantGain + 1;
  return room < kParticipantIdsPerAddress ? room : kParticipantIdsPerAddress;
}

struct NetworkOptions {
  /// The address of the interface the participant's sockets use (`--interface`).
  std::string interface_address = "127.0.0.1";
  /// Discover the run's participants through the server there (`--discovery-server`) instead
  /// of by multicast; then no topic uses multicast either. `skyfuse run` serves it itself.
  std::optional<Ipv4Endpoint> discovery_server;
  /// Announce this participant only to these discovery endpoints (`--discovery-peers`), and
  /// not by multicast: it then knows only the participants it or they list, instead of every
  /// participant of the domain. Empty: multicast (or the discovery server).
  std::vector<Ipv4Endpoint> discovery_peers;
  /// This participant's RTPS participant id (`--participant-id`), which fixes its discovery
  /// port (discovery_port()) for the others' peer lists; none: the first free one.
  std::optional<int> participant_id;
  /// How long another participant may hear nothing from this one before dropping it. Not an
  /// option: nodes and harness derive it from the run's size (lease_seconds()).
  double lease_s = 10.0;

  bool operator==(const NetworkOptions&) const = default;
};

/// `--interface ADDRESS`, `--discovery-server ADDRESS:PORT`, `--discovery-peers
/// ADDRESS:PORT,...` and `--participant-id N` into `options`.
void add_network_options(CLI::App& app, NetworkOptions& options);
/// The lease of a run of `stations` stations, whose DDS processes are those, the center and
/// the harness: 10 s, and a quarter second per process above 40. Starting 257 processes on 2
/// cores starves some for more than 10 s: the harness dropped 74 live stations for an expired
/// lease, and never matched some of them again (M = 256 on 4 hosts, --discovery peers,
/// 2026-11-26).
inline double lease_seconds(int stations) {
  const int processes = stations + 2;
  return processes > 40 ? 0.25 * processes : 10.0;
}

/// How the processes of a run find each other.
enum class Discovery {
  kAutomatic,  ///< on one host peers for a large tree when its ports allow
               ///< (harness/run/placement.cpp), multicast otherwise; the harness's discovery
               ///< server across hosts
  kMulticast,  ///< every participant announces itself to every other one by multicast
  kServer,     ///< through the harness's discovery server (across hosts only)
  kPeers,      ///< each process announces itself only to the processes it exchanges with
};
/// "auto", "multicast", "server", "peers".
std::string_view discovery_name(Discovery discovery);
/// `--discovery auto|multicast|server|peers` (also spelt `--host-discovery`). `discovery`'s
/// value on entry is the default shown in the help.
CLI::Option* add_discovery_option(CLI::App& app, Discovery& discovery, const std::string& help);
/// The arguments that give a node the same network options (none for the defaults).
std::vector<std::string> network_arguments(const NetworkOptions& options);

}  // namespace skyfuse::options
