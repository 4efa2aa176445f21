#pragma once
// `skyfuse certs DIR`: everything `skyfuse run --secure DIR` needs - a CA, one identity per
// node (and an observer), and the signed governance and permissions documents.

#include <CLI/App.hpp>
#include <string>

namespace skyfuse::harness {

/// Identities for at most this many stations: `skyfuse bench` and ring64.yaml go that far.
inline constexpr int kMaxCertifiedStations = 64;

struct CertsOptions {
  std::string dir;
  int stations = 0;  ///< 0: every station of the embedded scenario
};

void add_certs_command(CLI::App& app, CertsOptions& options);
int run_certs(const CertsOptions& options);

}  // namespace skyfuse::harness
