#pragma once
// The certificate authority of one `skyfuse certs` folder, made and used with Debian's openssl:
// an EC prime256v1 (P-256) key and a self-signed certificate, which then issues one key and
// certificate per identity and signs the governance and permissions documents.

#include <string>

#include "skyfuse/transport/security_folder.hpp"

namespace skyfuse::harness {

class CertificateAuthority {
 public:
  /// Creates the CA's key and certificate in `folder`, named `name` (so that two folders' CAs
  /// can be told apart in any message).
  CertificateAuthority(transport::SecurityFolder folder, std::string name);

  /// Writes `<identity>/key.pem` and `<identity>/cert.pem`, the certificate issued by this CA
  /// with the subject the permissions name.
  void issue_identity(const std::string& identity) const;

  /// Writes `text` to `source` and the CA's S/MIME signature of it to `signed_file`.
  void sign_document(const std::string& text, const std::filesystem::path& source,
                     const std::filesystem::path& signed_file) const;

  const std::string& name() const { return name_; }

 private:
  transport::SecurityFolder folder_;
  std::string name_;
};

}  // namespace skyfuse::harness
