#pragma once
/// \file
/// Whether another process's socket holds a multicast port a domain's nodes must share.
///
/// Every node of a domain binds the domain's multicast ports (discovery, the one-to-many
/// topics) with SO_REUSEADDR, so they share them. A socket bound to such a port without it -
/// typically some process's ephemeral send port, which Linux hands out from 32768-60999, where
/// the ports of domains 102 and up lie - keeps Fast DDS from opening the port, and Fast DDS says
/// nothing: the samples sent there never arrive (a lock-step run then ends "round 0
/// incomplete"). Measured here by binding domain 110's increment port before a run.

#include <optional>
#include <string>

namespace skyfuse::transport {

/// The first of `domain_id`'s multicast ports (discovery, user traffic, the one-to-many
/// topics) that a socket sharing it as Fast DDS does could not bind, described for a message;
/// nothing if each could.
std::optional<std::string> taken_multicast_port(int domain_id);

}  // namespace skyfuse::transport
