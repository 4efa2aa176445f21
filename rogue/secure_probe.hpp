#pragma once
// What skyfuse-rogue needs to probe a secure run: a DDS-Security identity of its choosing (any
// identity of any `skyfuse certs` folder, the run's or another CA's) and the probe mode, which
// tries to speak for a station and listens to what the run sends.

#include <CLI/App.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "skyfuse/options/network_options.hpp"
#include "skyfuse/transport/security.hpp"

namespace skyfuse::rogue {

/// The probe's identity may not publish: DDS-Security's access control refused its writer.
inline constexpr int kExitPublishRefused = 7;

struct ProbeOptions {
  std::optional<std::string> secure_dir;
  std::string identity = "observer";
  bool probe = false;

  /// The participant's security: none without --secure.
  std::optional<transport::SecurityConfig> security() const;
};

void add_probe_options(CLI::App& app, ProbeOptions& options);

struct ProbeTarget {
  int domain = 0;
  std::uint64_t run_id = 0;
  int victim = 0;     ///< the station the probe speaks for
  int state_dim = 0;  ///< of the run's motion model: what its increments are of
  double duration_s = 60.0;
  options::NetworkOptions network;  ///< the interface and discovery of the run
};

/// Speaks for the victim station on the increment and measurement topics every 10 ms and counts
/// every increment and measurement it hears from others, until SIGINT/SIGTERM or the duration
/// ends; then prints what it sent, heard and matched. Returns kExitPublishRefused, with the
/// reason, if its identity may not publish.
int run_probe(const ProbeOptions& options, const ProbeTarget& target);

}  // namespace skyfuse::rogue
