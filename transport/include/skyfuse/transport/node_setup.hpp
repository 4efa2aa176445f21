#pragma once
/// \file
/// What a node process builds from its command-line options: its DDS participant's settings
/// (its run plan: node_plan.hpp).

#include <string>

#include "skyfuse/options/node_options.hpp"
#include "skyfuse/sim/run_plan.hpp"
#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::transport {

/// Why a discovery server (`--discovery-server`, `--hosts`) and `--secure` are refused together:
/// measured, Debian's Fast DDS 2.9 (built with assertions) aborts the secure server participant
/// as the first clients join.
inline constexpr const char* kSecureDiscoveryServerRefusal =
    "--secure with a discovery server (--discovery-server, --hosts): Fast DDS 2.9 aborts a "
    "secure discovery server (assertion in SecurityManager::encode_rtps_message); use "
    "multicast discovery for secure runs";

/// The participant settings of the node called `name` (its security identity follows the
/// name).
NodeConfig node_config(const options::NodeOptions& options, const std::string& name);

}  // namespace skyfuse::transport
