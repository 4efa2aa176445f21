#pragma once
/// \file
/// Opt-in DDS-Security for a participant: authentication (builtin PKI-DH), access control
/// (builtin Access-Permissions) and encryption (builtin AES-GCM-GMAC), each node with its own
/// identity from a folder written by `skyfuse certs` (see security_folder.hpp).
///
/// What is protected, and how, comes from the signed governance document: discovery, liveliness
/// and every RTPS message encrypted, no unauthenticated participant admitted. Who may publish
/// or subscribe to which topic comes from the signed permissions document.

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "skyfuse/transport/node_config.hpp"

namespace skyfuse::transport {

/// Adds the security plugins' properties for `config.identity` to `qos`. Throws
/// SecurityFolderError if the folder lacks a file this identity needs.
void add_security_properties(eprosima::fastdds::dds::DomainParticipantQos& qos,
                             const SecurityConfig& config);

}  // namespace skyfuse::transport
