#include "security/certificate_authority.hpp"

#include "report/output_files.hpp"
#include "security/openssl_cli.hpp"
#include "security/security_documents.hpp"

namespace skyfuse::harness {
namespace {

// Ten years: these identities live as long as a test bed, and expiry is not what they guard.
constexpr const char* kValidityDays = "3650";
constexpr const char* kCurve = "ec_paramgen_curve:prime256v1";

}  // namespace

CertificateAuthority::CertificateAuthority(transport::SecurityFolder folder, std::string name)
    : folder_(std::move(folder)), name_(std::move(name)) {
  run_openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", kCurve, "-out",
               folder_.ca_private_key().string()});
  run_openssl({"req", "-x509", "-new", "-sha256", "-days", kValidityDays, "-key",
               folder_.ca_private_key().string(), "-subj", "/O=skyfuse/CN=" + name_, "-addext",
               "basicConstraints=critical,CA:TRUE", "-addext",
               // digitalSignature too: the CA signs the governance and permissions documents
               // itself, and S/MIME verification refuses a signer without it.
               "keyUsage=critical,keyCertSign,cRLSign,digitalSignature", "-out",
               folder_.ca_certificate().string()});
}

void CertificateAuthority::issue_identity(const std::string& identity) const {
  std::filesystem::create_directories(folder_.identity_dir(identity));
  // One command: a fresh key, and a certificate for it signed by the CA (no request file).
  run_openssl({"req",
               "-new",
               "-newkey",
               "ec",
               "-pkeyopt",
               kCurve,
               "-noenc",
               "-keyout",
               folder_.private_key(identity).string(),
               "-subj",
               openssl_subject(identity),
               "-x509",
               "-CA",
               folder_.ca_certificate().string(),
               "-CAkey",
               folder_.ca_private_key().string(),
               "-sha256",
               "-days",
               kValidityDays,
               "-addext",
               "basicConstraints=critical,CA:FALSE",
               "-addext",
               "keyUsage=critical,digitalSignature",
               "-out",
               folder_.certificate(identity).string()});
}

void CertificateAuthority::sign_document(const std::string& text,
                                         const std::filesystem::path& source,
                                         const std::filesystem::path& signed_file) const {
  write_file_atomically(source, text);
  // -text: the signed part carries a text/plain header, the form the security plugins read.
  run_openssl({"smime", "-sign", "-text", "-in", source.string(), "-out", signed_file.string(),
               "-signer", folder_.ca_certificate().string(), "-inkey",
               folder_.ca_private_key().string()});
}

}  // namespace skyfuse::harness
