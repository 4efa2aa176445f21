#include "run/placement.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

#include "run/discovery_peers.hpp"
#include "skyfuse/transport/node_setup.hpp"

namespace skyfuse::harness {

namespace {

using options::Discovery;

bool multicast_across_hosts(Discovery discovery) {
  // Peers announce by unicast, but ticks, measurements and increments still travel by
  // multicast, so the hosts' interfaces must carry it.
  return discovery == Discovery::kMulticast || discovery == Discovery::kPeers;
}

// The harness is participant 0 of its address; one host's processes follow it.
constexpr int kHarnessParticipantId = 0;

StationGroups groups_of(const RunOptions& o, std::size_t stations) {
  return {stations, static_cast<std::size_t>(o.stations_per_process)};
}

// Several stations in one process share its participant: one identity for DDS-Security, one
// process for the harness to kill, a command line the harness writes.
void check_stations_per_process(const RunOptions& o) {
  if (o.stations_per_process == 1) return;
  const auto refuse = [](const char* what) {
    throw std::invalid_argument(fmt::format("--stations-per-process: not with {}", what));
  };
  if (o.node.secure_dir) refuse("--secure (DDS-Security authenticates one station per process)");
  if (o.external) refuse("--external (the harness starts the processes it groups)");
  if (!o.kills.empty() || !o.restarts.empty()) {
    refuse("--kill or --restart (a kill would take every station of the process)");
  }
}

// The harness writes every node's peer list and participant id, so it must start the nodes,
// and their ids must fit the domain's ports on each address.
void check_peer_discovery(const RunOptions& o, std::size_t stations) {
  if (o.external) {
    throw std::invalid_argument("--discovery peers: not with --external (it lists the nodes)");
  }
  if (o.node.secure_dir) {
    throw std::invalid_argument(
        "--discovery peers: not with --secure (secure runs discover by multicast)");
  }
  const auto hosts = static_cast<std::size_t>(o.hosts);
  const std::size_t processes = groups_of(o, stations).processes();
  const std::size_t per_address = hosts > 0 ? (processes + hosts - 1) / hosts  // round robin
                                            : processes + 1;  // with the harness on one host
  const int room = options::participant_ids_per_address(o.node.domain);
  if (per_address > static_cast<std::size_t>(room)) {
    throw std::invalid_argument(fmt::format(
        "--discovery peers: {} processes on one address, and domain {} has room for {} there; "
        "spread them with --hosts{}",
        per_address, o.node.domain, room, o.node.domain > 200 ? " or take a lower --domain" : ""));
  }
}

// Whether a UDP socket could bind `port` on `address` now.
bool udp_port_free(const std::string& address, std::uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return true;  // nothing to learn: let Fast DDS try
  sockaddr_in where{};
  where.sin_family = AF_INET;
  where.sin_port = htons(port);
  const bool parsed = ::inet_pton(AF_INET, address.c_str(), &where.sin_addr) == 1;
  const bool bound =
      !parsed || ::bind(fd, reinterpret_cast<const sockaddr*>(&where), sizeof(where)) == 0;
  ::close(fd);
  return bound;
}

// Peer discovery fixes every participant's unicast ports (discovery, then data). One held by
// another socket - another DDS participant of the domain, or any socket the kernel gave it
// from its ephemeral range (32768-60999 here, which domains from 102 on reach) - leaves that
// participant unannounced, and the run times out in discovery: holding participant 42's port
// of domain 139 (station 41 of ring64) reproduced the one such failure seen. The first port
// another socket holds, described; none if every one is free.
std::optional<std::string> held_peer_port(const std::string& address, int domain,
                                          std::size_t participants) {
  for (std::size_t id = 0; id < participants; ++id) {
    const std::uint16_t discovery = options::discovery_port(domain, static_cast<int>(id));
    for (const std::uint16_t port : {discovery, static_cast<std::uint16_t>(discovery + 1)}) {
      if (udp_port_free(address, port)) continue;
      return fmt::format(
          "UDP port {} on {} (participant {} of domain {}: 0 the harness, 1 the center, then the "
          "stations in ascending id) is held by another socket",
          port, address, id, domain);
    }
  }
  return std::nullopt;
}

// The first port of the kernel's ephemeral range: a port from there may be any socket's at
// any moment.
int ephemeral_ports_from() {
  std::ifstream range("/proc/sys/net/ipv4/ip_local_port_range");
  int first = 32768;
  range >> first;
  return first > 0 ? first : 32768;
}

// `auto` on one host: the processes announce themselves to their exchange partners only
// (peers) for a tree of kPeersFromStations stations or more that the harness starts, without
// --secure or a network of one's own, when every fixed port lies below the kernel's ephemeral
// range and is free; multicast otherwise. Ring64, tree of 8, M = 64, 2-core AMD EPYC
// (2026-11-27): lock-step 113-131 rounds/s with peers against 83 with multicast; at 50 Hz with
// a 15 ms deadline 99.8-100 % of rounds in time against 96.6-99.6 % (docs/networks.md).
constexpr std::size_t kPeersFromStations = 16;

Discovery chosen_discovery(const RunOptions& o, const ExchangeConfig& exchange,
                           std::size_t stations) {
  if (o.discovery != Discovery::kAutomatic) return o.discovery;
  const bool one_host_as_started = o.hosts == 0 && !o.external && !o.node.secure_dir &&
                                   o.node.network == options::NetworkOptions{};
  if (!one_host_as_started || exchange.kind != ExchangeConfig::Kind::kTree ||
      stations < kPeersFromStations) {
    return Discovery::kAutomatic;
  }
  const std::size_t participants = groups_of(o, stations).processes() + 1;
  if (participants >
      static_cast<std::size_t>(options::participant_ids_per_address(o.node.domain))) {
    return Discovery::kAutomatic;
  }
  const int last_port =
      options::discovery_port(o.node.domain, static_cast<int>(participants) - 1) + 1;
  if (last_port >= ephemeral_ports_from() ||
      held_peer_port(o.node.network.interface_address, o.node.domain, participants)) {
    return Discovery::kAutomatic;
  }
  return Discovery::kPeers;
}

}  // namespace

int Placement::auto_stations_per_process(const RunOptions& o, std::size_t stations) {
  const bool grouping_refused =
      o.node.secure_dir || o.external || !o.kills.empty() || !o.restarts.empty();
  if (stations <= kStationsAlone || grouping_refused) return 1;
  int k = 1;
  while (static_cast<std::size_t>(k) * static_cast<std::size_t>(k) < stations) ++k;
  return k;
}

void Placement::check(const RunOptions& o, std::size_t stations) {
  if (o.node.secure_dir && (o.hosts > 0 || o.node.network.discovery_server)) {
    throw std::invalid_argument(transport::kSecureDiscoveryServerRefusal);
  }
  if (o.discovery == Discovery::kServer && o.hosts == 0) {
    throw std::invalid_argument(
        "--discovery server: the harness serves discovery for --hosts only; on one host give "
        "--discovery-server ADDRESS:PORT of a server of your own");
  }
  check_stations_per_process(o);
  if (o.discovery == Discovery::kPeers) check_peer_discovery(o, stations);
  const bool network_given = o.node.network != options::NetworkOptions{};
  if (network_given && (o.hosts > 0 || o.discovery == Discovery::kPeers)) {
    throw std::invalid_argument(
        fmt::format("{}: gives every node its interface and discovery; leave out --interface and "
                    "--discovery-server",
                    o.hosts > 0 ? "--hosts" : "--discovery peers"));
  }
  if (o.hosts == 0) return;
  if (o.external) throw std::invalid_argument("--hosts: not with --external (it starts the nodes)");
  SimulatedHosts::check_allowed(o.hosts);
}

Placement::Placement(const RunOptions& o, const ExchangeConfig& exchange, std::size_t stations)
    : domain_(o.node.domain), harness_(o.node.network) {
  check(o, stations);
  const Discovery discovery = chosen_discovery(o, exchange, stations);
  if (o.hosts > 0) {
    hosts_.emplace(o.hosts, multicast_across_hosts(o.discovery));
    harness_.interface_address = hosts_->bridge_address();
    if (o.discovery == Discovery::kAutomatic || o.discovery == Discovery::kServer) {
      harness_.discovery_server =
          options::Ipv4Endpoint{hosts_->bridge_address(), options::kDefaultDiscoveryPort};
    }
  }
  if (discovery == Discovery::kPeers) {
    peer_lists_ = discovery_peer_lists(exchange, stations, groups_of(o, stations));
    // On one host every port is on the harness's address (simulated hosts have their own);
    // `auto` chose peers only with every port free.
    if (!hosts_ && o.discovery == Discovery::kPeers) {
      if (const auto held = held_peer_port(harness_.interface_address, domain_,
                                           groups_of(o, stations).processes() + 1)) {
        throw std::invalid_argument(fmt::format(
            "--discovery peers: {}; free it or take another --domain (below 102 keeps every "
            "port out of the kernel's ephemeral range)",
            *held));
      }
    }
    harness_.participant_id = kHarnessParticipantId;
    for (std::size_t i = 0; i < peer_lists_.size(); ++i) {
      harness_.discovery_peers.push_back(discovery_endpoint(i));
    }
  }
}

int Placement::host_of(std::size_t i) const {
  return static_cast<int>(i % static_cast<std::size_t>(hosts_->count()));
}

std::string Placement::address(std::size_t i) const {
  return hosts_ ? hosts_->address(host_of(i)) : harness_.interface_address;
}

int Placement::participant_id(std::size_t i) const {
  // On one host the processes follow the harness; on simulated hosts each host numbers its
  // own from 0 (the harness is on the bridge's address).
  if (!hosts_) return kHarnessParticipantId + 1 + static_cast<int>(i);
  return static_cast<int>(i / static_cast<std::size_t>(hosts_->count()));
}

options::Ipv4Endpoint Placement::discovery_endpoint(std::size_t i) const {
  return {address(i), options::discovery_port(domain_, participant_id(i))};
}

std::pair<options::NetworkOptions, int> Placement::of(std::size_t i) const {
  options::NetworkOptions network = harness_;
  network.interface_address = address(i);
  if (!peer_lists_.empty()) {
    network.participant_id = participant_id(i);
    network.discovery_peers = {
        {harness_.interface_address, options::discovery_port(domain_, kHarnessParticipantId)}};
    for (std::size_t peer : peer_lists_.at(i)) {
      network.discovery_peers.push_back(discovery_endpoint(peer));
    }
  }
  return {network, hosts_ ? hosts_->namespace_fd(host_of(i)) : -1};
}

std::string Placement::discovery() const {
  if (!peer_lists_.empty()) return "peers";
  if (harness_.discovery_server) return "server " + harness_.discovery_server->to_string();
  return "multicast";
}

}  // namespace skyfuse::harness
