#pragma once
/// \file
/// What a node needs to say about its DDS participant, and the few DDS facts the rest of the
/// program shares, without Fast DDS's headers: included by option parsing, the harness and the
/// sample checks, which should not pay for compiling Fast DDS on 2 cores.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "skyfuse/options/node_options.hpp"

namespace skyfuse::transport {

struct SecurityConfig {
  std::filesystem::path dir;  ///< written by `skyfuse certs`
  std::string identity;       ///< "harness", "center", "station-3", "observer"
};

/// A DDS call failed: entity creation, or a write that could not be delivered in time.
class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NodeConfig {
  int domain_id = 0;
  std::string name;  ///< participant name, shown by DDS tools
  std::optional<std::filesystem::path> qos_file;
  /// Increments and measurements travel BEST_EFFORT (`--best-effort`): a lost datagram is
  /// not repaired, and a round closes at its deadline without the sample.
  bool best_effort_data = false;
  std::optional<SecurityConfig> security;  ///< none: plain DDS
  /// The interface the sockets use and the discovery: multicast, or as a client of
  /// network.discovery_server.
  options::NetworkOptions network;
  /// This participant is the discovery server at network.discovery_server (the harness).
  bool serves_discovery = false;
};

/// Domain ids above 232 make Fast DDS 2.9 exit the process during participant creation.
inline constexpr int kMaxDomainId = options::kMaxDomainId;

/// Which writer a sample came from: its DDS instance handle (the writer's GUID), as bytes.
using WriterId = std::array<std::uint8_t, 16>;

}  // namespace skyfuse::transport
