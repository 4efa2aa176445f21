#pragma once
// The two XML documents of DDS-Security's builtin access control, as text. The CA signs them
// (S/MIME) before any participant loads them; see certs_command.cpp.

#include <chrono>
#include <string>
#include <vector>

#include "security/access_grants.hpp"

namespace skyfuse::harness {

/// Every skyfuse topic, for the governance rules.
std::vector<std::string> skyfuse_topics();

/// Domain rules for every domain id skyfuse accepts: no unauthenticated participant, join
/// access control, discovery, liveliness and whole RTPS messages encrypted, and for each topic
/// read and write access control with metadata and data encrypted.
std::string governance_xml(const std::vector<std::string>& topics);

/// The certificate subject of an identity, in the RFC 2253 order the permissions use.
std::string subject_name(const std::string& identity);
/// The same subject in the form `openssl req -subj` takes.
std::string openssl_subject(const std::string& identity);

/// One grant per identity, valid from `not_before` to `not_after`; anything not allowed is
/// denied.
std::string permissions_xml(const std::vector<AccessGrant>& grants,
                            std::chrono::system_clock::time_point not_before,
                            std::chrono::system_clock::time_point not_after);

}  // namespace skyfuse::harness
