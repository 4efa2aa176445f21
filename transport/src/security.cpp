#include "skyfuse/transport/security.hpp"

#include "skyfuse/transport/security_folder.hpp"

namespace skyfuse::transport {
namespace {

// The security plugins read their files through URIs; a bare path is not accepted.
std::string file_uri(const std::filesystem::path& path) {
  return "file://" + std::filesystem::absolute(path).string();
}

}  // namespace

void add_security_properties(eprosima::fastdds::dds::DomainParticipantQos& qos,
                             const SecurityConfig& config) {
  const SecurityFolder folder{config.dir};
  folder.check({config.identity});

  auto& properties = qos.properties().properties();
  const auto set = [&](const std::string& name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", file_uri(folder.ca_certificate()));
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate",
      file_uri(folder.certificate(config.identity)));
  set("dds.sec.auth.builtin.PKI-DH.private_key", file_uri(folder.private_key(config.identity)));

  // Without access control the crypto plugin would send plaintext: protection levels come only
  // from the governance document, which this plugin enforces.
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca",
      file_uri(folder.ca_certificate()));
  set("dds.sec.access.builtin.Access-Permissions.governance", file_uri(folder.governance()));
  set("dds.sec.access.builtin.Access-Permissions.permissions", file_uri(folder.permissions()));

  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

}  // namespace skyfuse::transport
