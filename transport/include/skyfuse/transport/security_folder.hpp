#pragma once
/// \file
/// The folder `skyfuse certs DIR` writes and `--secure DIR` reads: one certificate authority,
/// the signed governance and permissions documents, and one identity (key and certificate) per
/// node. Both sides take every path from here, so writer and reader cannot disagree.
///
///   DIR/ca.pem, DIR/ca.key              the CA (identity CA and permissions CA)
///   DIR/governance.xml, .p7s            domain rules, and the same S/MIME-signed by the CA
///   DIR/permissions.xml, .p7s           one grant per identity, and the same signed
///   DIR/<identity>/cert.pem, key.pem    harness, center, station-1 ... station-N, observer
///   DIR/identities.txt                  every identity in the folder, one per line
///
/// A node's identity is its participant name without the "skyfuse-" prefix: skyfuse-station-3
/// is station-3, skyfuse-center is center, skyfuse-harness is harness.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace skyfuse::transport {

/// A --secure folder that cannot serve a node: a file missing, an identity it was not made for.
/// A usage error (exit code 2), since the fix is a command the message names.
class SecurityFolderError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

inline constexpr const char* kHarnessIdentity = "harness";
inline constexpr const char* kCenterIdentity = "center";
/// Valid certificate, subscribe-only permissions: a participant that may listen but not speak.
inline constexpr const char* kObserverIdentity = "observer";

std::string station_identity(int station_id);
bool is_station_identity(const std::string& identity);
std::string identity_for_participant(const std::string& participant_name);
/// Every identity a run of these stations needs: harness, center and one per station.
std::vector<std::string> run_identities(const std::vector<int>& station_ids);

struct SecurityFolder {
  std::filesystem::path dir;

  std::filesystem::path ca_certificate() const { return dir / "ca.pem"; }
  std::filesystem::path ca_private_key() const { return dir / "ca.key"; }
  std::filesystem::path governance_source() const { return dir / "governance.xml"; }
  std::filesystem::path governance() const { return dir / "governance.p7s"; }
  std::filesystem::path permissions_source() const { return dir / "permissions.xml"; }
  std::filesystem::path permissions() const { return dir / "permissions.p7s"; }
  std::filesystem::path manifest() const { return dir / "identities.txt"; }
  std::filesystem::path identity_dir(const std::string& identity) const { return dir / identity; }
  std::filesystem::path certificate(const std::string& identity) const {
    return identity_dir(identity) / "cert.pem";
  }
  std::filesystem::path private_key(const std::string& identity) const {
    return identity_dir(identity) / "key.pem";
  }

  /// The identities listed in the manifest; throws SecurityFolderError if it is missing.
  std::vector<std::string> listed_identities() const;
  /// Throws SecurityFolderError naming the first identity or file that is missing, and what
  /// to run instead.
  void check(const std::vector<std::string>& identities) const;
};

}  // namespace skyfuse::transport
